// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "splat_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

namespace freeform_inspection {
namespace {

// Rows right, up, toward the viewer from a viewing direction and a hint for "up".
Eigen::Matrix3d viewAxes(const Eigen::Vector3d& up_hint, const Eigen::Vector3d& toward) {
  const Eigen::Vector3d back = toward.normalized();
  const Eigen::Vector3d up = (up_hint - up_hint.dot(back) * back).normalized();
  Eigen::Matrix3d axes;
  axes.row(0) = up.cross(back);
  axes.row(1) = up;
  axes.row(2) = back;
  return axes;
}

// Eigenvectors have no sign: make the largest component positive so a part gives the same
// pictures on every run.
Eigen::Vector3d canonicalSign(const Eigen::Vector3d& axis) {
  Eigen::Index largest = 0;
  axis.cwiseAbs().maxCoeff(&largest);
  return axis[largest] < 0.0 ? Eigen::Vector3d(-axis) : axis;
}

// Points in view coordinates: x right, y up, z toward the viewer.
Points project(const Points& points, const Eigen::Matrix3d& axes) {
  Points projected;
  projected.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    projected.push_back(axes * p);
  }
  return projected;
}

// Where view coordinates land on the image: a uniform scale that fits the points, centred.
struct ImageMapping {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< [m] view coordinates of the image centre
  double pixels_per_metre = 1.0;
  double near = 0.0;     ///< [m] largest z
  double depth = 0.0;    ///< [m] z range
  int splat_radius = 1;  ///< [px] half the side of a square splat
};

// Half-side of a splat so that splats of neighbouring points meet: the mean spacing of the points
// spread over the area they cover on the image. A closed part shows only its front half, whose
// points lie about sqrt(2) times farther apart: a half-side of one spacing covers that too.
int splatRadius(std::size_t points, double covered_pixels) {
  const double spacing =
      std::sqrt(covered_pixels / static_cast<double>(std::max<std::size_t>(points, 1)));
  return static_cast<int>(std::clamp(std::lround(spacing), 1L, 12L));
}

ImageMapping fitToImage(const Points& projected, const SplatConfig& config) {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (const Eigen::Vector3d& p : projected) {
    if (p.allFinite()) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  }
  const Eigen::Vector3d span = (high - low).cwiseMax(1e-12);
  ImageMapping mapping;
  mapping.centre = 0.5 * (low + high);
  mapping.pixels_per_metre = std::min((config.width - 2 * config.margin) / span.x(),
                                      (config.height - 2 * config.margin) / span.y());
  mapping.near = high.z();
  mapping.depth = span.z();
  mapping.splat_radius = splatRadius(
      projected.size(), span.x() * span.y() * mapping.pixels_per_metre * mapping.pixels_per_metre);
  return mapping;
}

Rgb shaded(const Rgb& colour, double factor) {
  Rgb out;
  for (std::size_t c = 0; c < 3; ++c) {
    out[c] = static_cast<std::uint8_t>(std::lround(colour[c] * factor));
  }
  return out;
}

// One square splat, kept where it is nearer than what the z-buffer holds.
void splat(const Eigen::Vector3d& p,
           const Rgb& colour,
           const ImageMapping& mapping,
           std::vector<double>* z_buffer,
           RgbImage* image) {
  const long cx =
      std::lround(image->width / 2.0 + (p.x() - mapping.centre.x()) * mapping.pixels_per_metre);
  const long cy =
      std::lround(image->height / 2.0 - (p.y() - mapping.centre.y()) * mapping.pixels_per_metre);
  const long r = mapping.splat_radius;
  for (long y = std::max(cy - r, 0L); y <= std::min(cy + r, long{image->height} - 1); ++y) {
    for (long x = std::max(cx - r, 0L); x <= std::min(cx + r, long{image->width} - 1); ++x) {
      double& z = (*z_buffer)[static_cast<std::size_t>(y * image->width + x)];
      if (p.z() > z) {
        z = p.z();
        image->set(static_cast<int>(x), static_cast<int>(y), colour);
      }
    }
  }
}

}  // namespace

std::vector<OrthoView> principalViews(const Points& points) {
  Eigen::Vector3d e1 = Eigen::Vector3d::UnitX();
  Eigen::Vector3d e2 = Eigen::Vector3d::UnitY();
  if (points.size() >= 3) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : points) {
      mean += p;
    }
    mean /= static_cast<double>(points.size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (const Eigen::Vector3d& p : points) {
      scatter += (p - mean) * (p - mean).transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);  // ascending
    e1 = canonicalSign(solver.eigenvectors().col(2));
    e2 = canonicalSign(solver.eigenvectors().col(1));
  }
  const Eigen::Vector3d e3 = e1.cross(e2);
  return {{"front", viewAxes(e2, e3)},
          {"back", viewAxes(e2, -e3)},
          {"isometric", viewAxes(e2, e1 + e2 + e3)}};
}

RgbImage renderSplats(const Points& points,
                      const std::vector<Rgb>& colours,
                      const OrthoView& view,
                      const SplatConfig& config) {
  RgbImage image = RgbImage::filled(config.width, config.height, config.background);
  if (points.empty() || colours.size() != points.size()) {
    return image;
  }
  const Points projected = project(points, view.axes);
  const ImageMapping mapping = fitToImage(projected, config);
  std::vector<double> z_buffer(image.pixels.size() / 3, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < projected.size(); ++i) {
    if (!projected[i].allFinite()) {
      continue;
    }
    // Depth cue: farther points darker, so the shape reads without lighting.
    const double farness =
        mapping.depth > 0.0 ? (mapping.near - projected[i].z()) / mapping.depth : 0.0;
    splat(projected[i],
          shaded(colours[i], std::clamp(1.0 - config.depth_shading * farness, 0.0, 1.0)),
          mapping,
          &z_buffer,
          &image);
  }
  return image;
}

}  // namespace freeform_inspection
