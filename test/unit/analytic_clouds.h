// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Geometry>

#include "freeform_inspection/types.h"

/// Point clouds on surfaces with known curvature and exact normals, for the curvature and
/// triangulation tests. Random samplers are deterministic for a seed (std::mt19937); organized
/// variants are range images of a pinhole sensor at the origin looking along +z.
namespace freeform_inspection::analytic {

constexpr double kPi = 3.14159265358979323846;

/// Points with one exact unit normal each.
struct Cloud {
  Points points;
  Points normals;
};

/// A width × height range image, row-major; points and normals are NaN where the ray misses.
struct OrganizedCloud {
  int width = 0;
  int height = 0;
  Points points;
  Points normals;
};

/// Pinhole sensor at the origin looking along +z (x right, y down, like a camera), principal
/// point at the image centre.
struct Pinhole {
  int width = 0;
  int height = 0;
  double focal = 1.0;  ///< [pixels]

  /// Ray direction through a pixel, scaled so that its z component is 1 (t = depth).
  Eigen::Vector3d ray(int row, int column) const {
    return {(column - 0.5 * (width - 1)) / focal, (row - 0.5 * (height - 1)) / focal, 1.0};
  }
};

/// Where a ray meets a surface: depth t along the ray (NaN when it misses) and the normal.
struct Hit {
  double t = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector3d normal = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
};

inline Eigen::Vector3d uniformDirection(std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Vector3d d;
  do {
    d = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
  } while (d.squaredNorm() < 1e-12);
  return d.normalized();
}

/// Uniform on a sphere about the origin, outward normals. H = 1/R.
inline Cloud sampleSphere(double radius, int count, unsigned seed) {
  std::mt19937 rng(seed);
  Cloud cloud;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d n = uniformDirection(rng);
    cloud.points.push_back(radius * n);
    cloud.normals.push_back(n);
  }
  return cloud;
}

/// Uniform on the side of an open cylinder about the z axis, |z| ≤ length/2, outward normals.
/// H = 1/(2R).
inline Cloud sampleCylinder(double radius, double length, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * kPi);
  std::uniform_real_distribution<double> height(-0.5 * length, 0.5 * length);
  Cloud cloud;
  for (int i = 0; i < count; ++i) {
    const double phi = angle(rng);
    const Eigen::Vector3d n(std::cos(phi), std::sin(phi), 0.0);
    cloud.points.push_back(radius * n + Eigen::Vector3d(0.0, 0.0, height(rng)));
    cloud.normals.push_back(n);
  }
  return cloud;
}

/// Uniform on the square |x|, |y| ≤ side/2 of the plane z = 0, normals +z. H = 0.
inline Cloud samplePlane(double side, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(-0.5 * side, 0.5 * side);
  Cloud cloud;
  for (int i = 0; i < count; ++i) {
    const double x = coordinate(rng);
    cloud.points.emplace_back(x, coordinate(rng), 0.0);
    cloud.normals.push_back(Eigen::Vector3d::UnitZ());
  }
  return cloud;
}

/// Unit normal of the saddle z = (x² − y²)/(2s) on its +z side.
inline Eigen::Vector3d saddleNormal(double x, double y, double scale) {
  return Eigen::Vector3d(-x / scale, y / scale, 1.0).normalized();
}

/// Mean curvature of the saddle z = (x² − y²)/(2s) with its +z normal, in the package's sign
/// (bending away from the normal is positive): principal curvatures ∓1/s at the origin, H = 0.
inline double saddleMeanCurvature(double x, double y, double scale) {
  const double g = 1.0 + (x * x + y * y) / (scale * scale);
  return (x * x - y * y) / (2.0 * scale * scale * scale * std::pow(g, 1.5));
}

/// The saddle z = (x² − y²)/(2s) over |x|, |y| ≤ side/2 (uniform in x, y), +z normals.
inline Cloud sampleSaddle(double scale, double side, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(-0.5 * side, 0.5 * side);
  Cloud cloud;
  for (int i = 0; i < count; ++i) {
    const double x = coordinate(rng);
    const double y = coordinate(rng);
    cloud.points.emplace_back(x, y, (x * x - y * y) / (2.0 * scale));
    cloud.normals.push_back(saddleNormal(x, y, scale));
  }
  return cloud;
}

/// Range image of any surface: `intersect(ray)` returns the Hit of a ray (z component 1).
template <class Intersect>
OrganizedCloud renderOrganized(const Pinhole& camera, Intersect intersect) {
  OrganizedCloud cloud;
  cloud.width = camera.width;
  cloud.height = camera.height;
  for (int row = 0; row < camera.height; ++row) {
    for (int column = 0; column < camera.width; ++column) {
      const Eigen::Vector3d ray = camera.ray(row, column);
      const Hit hit = intersect(ray);
      // A miss has t = NaN, so t·ray is the all-NaN point a scanner stores for "no return".
      cloud.points.push_back(hit.t * ray);
      cloud.normals.push_back(hit.normal);
    }
  }
  return cloud;
}

/// Sphere of `radius` about `centre` (the origin outside it), outward normals (facing the
/// sensor where seen). NaN outside the silhouette.
inline OrganizedCloud organizedSphere(const Pinhole& camera,
                                      const Eigen::Vector3d& centre,
                                      double radius) {
  return renderOrganized(camera, [&](const Eigen::Vector3d& d) {
    const double dc = d.dot(centre);
    const double disc = dc * dc - d.squaredNorm() * (centre.squaredNorm() - radius * radius);
    Hit hit;
    if (disc >= 0.0) {
      hit.t = (dc - std::sqrt(disc)) / d.squaredNorm();
      hit.normal = (hit.t * d - centre) / radius;
    }
    return hit;
  });
}

/// Cylinder of `radius` about the line x = 0, z = depth (parallel to y), outward normals.
inline OrganizedCloud organizedCylinder(const Pinhole& camera, double depth, double radius) {
  return renderOrganized(camera, [&](const Eigen::Vector3d& d) {
    const double a = d.x() * d.x() + 1.0;
    const double disc = depth * depth - a * (depth * depth - radius * radius);
    Hit hit;
    if (disc >= 0.0) {
      hit.t = (depth - std::sqrt(disc)) / a;
      hit.normal = Eigen::Vector3d(hit.t * d.x(), 0.0, hit.t - depth) / radius;
    }
    return hit;
  });
}

/// Plane n·p = offset (offset > 0), normals facing the sensor (−n).
inline OrganizedCloud organizedPlane(const Pinhole& camera,
                                     const Eigen::Vector3d& normal,
                                     double offset) {
  const Eigen::Vector3d n = normal.normalized();
  return renderOrganized(camera, [&](const Eigen::Vector3d& d) {
    Hit hit;
    const double t = offset / n.dot(d);
    if (std::isfinite(t) && t > 0.0) {
      hit.t = t;
      hit.normal = -n;
    }
    return hit;
  });
}

/// Saddle z = depth + (x² − y²)/(2s), normals facing the sensor (−z side): with that normal
/// H(x, y) = −saddleMeanCurvature(x, y, s).
inline OrganizedCloud organizedSaddle(const Pinhole& camera, double depth, double scale) {
  return renderOrganized(camera, [&](const Eigen::Vector3d& d) {
    // t = depth + q t², q = (dx² − dy²)/(2s); the stable root that tends to depth as q → 0.
    const double q = (d.x() * d.x() - d.y() * d.y()) / (2.0 * scale);
    const double disc = 1.0 - 4.0 * q * depth;
    Hit hit;
    if (disc >= 0.0) {
      hit.t = 2.0 * depth / (1.0 + std::sqrt(disc));
      hit.normal = -saddleNormal(hit.t * d.x(), hit.t * d.y(), scale);
    }
    return hit;
  });
}

/// The finite points of an organized cloud with their normals, in row-major order.
inline Cloud finitePart(const OrganizedCloud& organized) {
  Cloud cloud;
  for (std::size_t i = 0; i < organized.points.size(); ++i) {
    if (organized.points[i].allFinite()) {
      cloud.points.push_back(organized.points[i]);
      cloud.normals.push_back(organized.normals[i]);
    }
  }
  return cloud;
}

}  // namespace freeform_inspection::analytic
