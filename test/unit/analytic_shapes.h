// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <unordered_map>
#include <utility>

#include <Eigen/Geometry>

#include "freeform_inspection/types.h"

/// @file analytic_shapes.h
/// Triangle meshes of surfaces with known curvature, built in code for the unit tests. Every
/// generator returns faces counter-clockwise seen from outside (outward normals; +z for the
/// height fields) and leaves `face_normals` empty. Header-only, no other test header needed.
namespace freeform_inspection::test {

constexpr double kShapePi = 3.14159265358979323846;

/// Closed icosahedral sphere centred at the origin: every face split in four `subdivisions`
/// times, new vertices projected onto the sphere. V = 10·4^s + 2, F = 20·4^s.
inline TriangleMesh icosphere(double radius, int subdivisions) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh mesh;
  mesh.vertices = {{-1.0, t, 0.0},
                   {1.0, t, 0.0},
                   {-1.0, -t, 0.0},
                   {1.0, -t, 0.0},
                   {0.0, -1.0, t},
                   {0.0, 1.0, t},
                   {0.0, -1.0, -t},
                   {0.0, 1.0, -t},
                   {t, 0.0, -1.0},
                   {t, 0.0, 1.0},
                   {-t, 0.0, -1.0},
                   {-t, 0.0, 1.0}};
  mesh.faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& v : mesh.vertices) {
    v = radius * v.normalized();
  }
  for (int s = 0; s < subdivisions; ++s) {
    std::unordered_map<std::uint64_t, int> midpoint;
    auto split = [&](int a, int b) {
      const auto key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
                       static_cast<std::uint64_t>(std::max(a, b));
      const auto found = midpoint.find(key);
      if (found != midpoint.end()) {
        return found->second;
      }
      const Eigen::Vector3d m =
          mesh.vertices[static_cast<std::size_t>(a)] + mesh.vertices[static_cast<std::size_t>(b)];
      mesh.vertices.push_back(radius * m.normalized());
      return midpoint[key] = static_cast<int>(mesh.vertices.size() - 1);
    };
    Triangles finer;
    finer.reserve(4 * mesh.faces.size());
    for (const auto& f : mesh.faces) {
      const int ab = split(f[0], f[1]);
      const int bc = split(f[1], f[2]);
      const int ca = split(f[2], f[0]);
      finer.insert(finer.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
    }
    mesh.faces.swap(finer);
  }
  return mesh;
}

/// Faces of a (rows + 1) × columns vertex lattice, vertex (i, j) at i·columns + j, wrapping in
/// j when `wrap`, quads split along (i, j)–(i+1, j+1). The face normal is ∂p/∂j × ∂p/∂i.
inline Triangles latticeFaces(int rows, int columns, bool wrap) {
  Triangles faces;
  const int spans = wrap ? columns : columns - 1;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < spans; ++j) {
      const int a = i * columns + j;
      const int b = i * columns + (j + 1) % columns;
      const int c = b + columns;
      const int d = a + columns;
      faces.push_back({a, b, c});
      faces.push_back({a, c, d});
    }
  }
  return faces;
}

/// Latitude-longitude sphere: `stacks` bands between the poles, `slices` around the z axis.
/// Pole vertices are single; triangles shrink towards the poles (an irregular tessellation).
inline TriangleMesh uvSphere(double radius, int stacks, int slices) {
  TriangleMesh mesh;
  for (int i = 1; i < stacks; ++i) {
    const double theta = kShapePi * i / stacks;  // from the north pole
    for (int j = 0; j < slices; ++j) {
      const double phi = 2.0 * kShapePi * j / slices;
      mesh.vertices.emplace_back(radius * std::sin(theta) * std::cos(phi),
                                 radius * std::sin(theta) * std::sin(phi),
                                 radius * std::cos(theta));
    }
  }
  // Bands run from north to south (−z): with j (east) first, i (south) second, the normal
  // east × south points inward, so the lattice faces are reversed.
  mesh.faces = latticeFaces(stacks - 2, slices, true);
  for (auto& f : mesh.faces) {
    std::swap(f[1], f[2]);
  }
  const int north = static_cast<int>(mesh.vertices.size());
  const int south = north + 1;
  mesh.vertices.emplace_back(0.0, 0.0, radius);
  mesh.vertices.emplace_back(0.0, 0.0, -radius);
  const int last_ring = (stacks - 2) * slices;
  for (int j = 0; j < slices; ++j) {
    const int next = (j + 1) % slices;
    mesh.faces.push_back({north, j, next});
    mesh.faces.push_back({south, last_ring + next, last_ring + j});
  }
  return mesh;
}

/// Open cylinder tube around the z axis, z in [−height/2, height/2]: `segments` around,
/// `rings` bands along z ((rings + 1) · segments vertices), two boundary circles.
inline TriangleMesh cylinderTube(double radius, double height, int segments, int rings) {
  TriangleMesh mesh;
  for (int i = 0; i <= rings; ++i) {
    const double z = height * (static_cast<double>(i) / rings - 0.5);
    for (int j = 0; j < segments; ++j) {
      const double phi = 2.0 * kShapePi * j / segments;
      mesh.vertices.emplace_back(radius * std::cos(phi), radius * std::sin(phi), z);
    }
  }
  mesh.faces = latticeFaces(rings, segments, true);  // around × up = outward
  return mesh;
}

/// Torus around the z axis: centre circle radius `major`, tube radius `minor`; u (around z,
/// `major_segments`) and v (around the tube, `minor_segments`, v = 0 on the outer equator).
/// Vertex (i, j) = (u_i, v_j) is at index i · minor_segments + j.
inline TriangleMesh torus(double major, double minor, int major_segments, int minor_segments) {
  TriangleMesh mesh;
  for (int i = 0; i < major_segments; ++i) {
    const double u = 2.0 * kShapePi * i / major_segments;
    for (int j = 0; j < minor_segments; ++j) {
      const double v = 2.0 * kShapePi * j / minor_segments;
      const double ring = major + minor * std::cos(v);
      mesh.vertices.emplace_back(ring * std::cos(u), ring * std::sin(u), minor * std::sin(v));
    }
  }
  // Rows are u (wrapping too), columns are v: ∂p/∂v × ∂p/∂u points inward, so reverse.
  mesh.faces = latticeFaces(major_segments, minor_segments, true);
  const int wrap = major_segments * minor_segments;
  for (auto& f : mesh.faces) {
    for (int c = 0; c < 3; ++c) {
      f[c] %= wrap;
    }
    std::swap(f[1], f[2]);
  }
  return mesh;
}

/// Grid of n × n cells on [−size/2, size/2]² at z = height(x, y), normals towards +z. Interior
/// vertices move in-plane by up to `jitter` cell widths (uniform, seeded), boundary ones stay.
template <typename Height>
TriangleMesh heightGrid(double size, int n, Height height, double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  const double cell = size / n;
  TriangleMesh mesh;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const bool interior = i > 0 && i < n && j > 0 && j < n;
      const double x = -size / 2.0 + cell * (j + (interior ? offset(rng) : 0.0));
      const double y = -size / 2.0 + cell * (i + (interior ? offset(rng) : 0.0));
      mesh.vertices.emplace_back(x, y, height(x, y));
    }
  }
  mesh.faces = latticeFaces(n, n + 1, false);  // x × y = +z
  return mesh;
}

/// Flat grid in the z = 0 plane ((n + 1)² vertices, 2n² faces, 4n boundary vertices).
inline TriangleMesh planarGrid(double size, int n, double jitter = 0.0, unsigned seed = 1) {
  return heightGrid(
      size, n, [](double, double) { return 0.0; }, jitter, seed);
}

/// Saddle z = (x² − y²)/(2a): at the origin k = ∓1/a, so H = 0 and K = −1/a². n even puts a
/// vertex at the origin, index (n/2)·(n + 1) + n/2.
inline TriangleMesh saddleGrid(double a, double size, int n) {
  return heightGrid(
      size, n, [a](double x, double y) { return (x * x - y * y) / (2.0 * a); }, 0.0, 1);
}

/// Unit area-weighted vertex normals (zero for vertices without faces).
inline Points vertexNormals(const TriangleMesh& mesh) {
  Points normals(mesh.vertices.size(), Eigen::Vector3d::Zero());
  for (const auto& f : mesh.faces) {
    const auto at = [&mesh, &f](int c) { return mesh.vertices[static_cast<std::size_t>(f[c])]; };
    const Eigen::Vector3d cross = (at(1) - at(0)).cross(at(2) - at(0));
    for (int c = 0; c < 3; ++c) {
      normals[static_cast<std::size_t>(f[c])] += cross;
    }
  }
  for (auto& n : normals) {
    n = n.norm() > 0.0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
  }
  return normals;
}

/// Moves every vertex along its normal by Gaussian noise of standard deviation `sigma`.
inline TriangleMesh addNormalNoise(TriangleMesh mesh, double sigma, unsigned seed) {
  const Points normals = vertexNormals(mesh);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    mesh.vertices[i] += noise(rng) * normals[i];
  }
  return mesh;
}

/// The same surface with every face reversed (normals pointing inward).
inline TriangleMesh flipped(TriangleMesh mesh) {
  for (auto& f : mesh.faces) {
    std::swap(f[1], f[2]);
  }
  return mesh;
}

}  // namespace freeform_inspection::test
