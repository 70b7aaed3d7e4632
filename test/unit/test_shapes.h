// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <random>

#include <Eigen/Geometry>

#include "freeform_inspection/types.h"

/// Shapes with known answers, built in code for the unit tests.
namespace freeform_inspection::test {

/// Closed axis-aligned box with outward faces, corners at ±half_extent. 8 vertices, 12 faces.
inline TriangleMesh makeBox(const Eigen::Vector3d& half_extent) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.emplace_back((i & 1 ? 1 : -1) * half_extent.x(),
                               (i & 2 ? 1 : -1) * half_extent.y(),
                               (i & 4 ? 1 : -1) * half_extent.z());
  }
  mesh.faces = {{0, 2, 1},
                {1, 2, 3},
                {4, 5, 6},
                {5, 7, 6},
                {0, 1, 4},
                {1, 5, 4},
                {2, 6, 3},
                {3, 6, 7},
                {0, 4, 2},
                {2, 4, 6},
                {1, 3, 5},
                {3, 7, 5}};
  return mesh;
}

/// Points on the surface of a box, uniform per face; deterministic for a seed.
inline Points sampleBoxSurface(const Eigen::Vector3d& half_extent, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> face(0, 5);
  Points points;
  for (int i = 0; i < count; ++i) {
    Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const int f = face(rng);
    p[f / 2] = f % 2 == 0 ? -1.0 : 1.0;
    points.push_back(p.cwiseProduct(half_extent));
  }
  return points;
}

}  // namespace freeform_inspection::test
