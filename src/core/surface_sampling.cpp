// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/surface_sampling.h"

#include <algorithm>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

std::vector<double> cumulativeAreas(const TriangleMesh& mesh) {
  std::vector<double> cumulative;
  cumulative.reserve(mesh.faces.size());
  double total = 0.0;
  for (const auto& f : mesh.faces) {
    total += triangleArea(mesh.vertices, f);
    cumulative.push_back(total);
  }
  return cumulative;
}

}  // namespace

SurfaceSample sampleSurface(const TriangleMesh& mesh,
                            std::size_t count,
                            unsigned seed,
                            double noise_sigma) {
  SurfaceSample sample;
  const std::vector<double> cumulative = cumulativeAreas(mesh);
  if (cumulative.empty() || !(cumulative.back() > 0.0)) {
    return sample;
  }
  const Points normals = computeFaceNormals(mesh.vertices, mesh.faces);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, noise_sigma > 0.0 ? noise_sigma : 1.0);
  for (std::size_t i = 0; i < count; ++i) {
    const double pick = uniform(rng) * cumulative.back();
    const auto face = static_cast<std::size_t>(
        std::lower_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin());
    const auto& f = mesh.faces[std::min(face, mesh.faces.size() - 1)];
    double a = uniform(rng);
    double b = uniform(rng);
    if (a + b > 1.0) {  // fold the square onto the triangle: uniform barycentric coordinates
      a = 1.0 - a;
      b = 1.0 - b;
    }
    const auto& v = mesh.vertices;
    const Eigen::Vector3d& p0 = v[static_cast<std::size_t>(f[0])];
    const Eigen::Vector3d n = normals[std::min(face, mesh.faces.size() - 1)];
    const double offset = noise_sigma > 0.0 ? noise(rng) : 0.0;
    sample.points.push_back(p0 + a * (v[static_cast<std::size_t>(f[1])] - p0) +
                            b * (v[static_cast<std::size_t>(f[2])] - p0) + offset * n);
    sample.normals.push_back(n);
  }
  return sample;
}

}  // namespace freeform_inspection
