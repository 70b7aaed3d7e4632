// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/synthetic_scan.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFacingThreshold = 0.05;  // n·d above this counts as seen by the sensor
constexpr double kRayOffsetRatio = 1e-6;   // × L: ray start off the surface, past its own face
constexpr double kOutlierBoxMargin = 0.1;  // outlier box: surface box grown by 10 % per side
constexpr int kMaxRounds = 8;              // partial views: sampling rounds before giving up
constexpr double kDefectFacingCos = 0.5;   // a defect moves the surface facing within 60° of it

// The std:: distributions are implementation-defined, mt19937_64's raw output is not: converting
// it by hand makes a case the same with any standard library.
double uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0);  // [0, 1), 53 bits
}

// Box-Muller; 1 − u keeps the logarithm finite.
double gaussian(std::mt19937_64& rng) {
  const double radius = std::sqrt(-2.0 * std::log(1.0 - uniform01(rng)));
  return radius * std::cos(2.0 * kPi * uniform01(rng));
}

// Uniform on the unit sphere: an isotropic Gaussian, normalized.
Eigen::Vector3d randomUnitVector(std::mt19937_64& rng) {
  Eigen::Vector3d v;
  do {
    v = Eigen::Vector3d(gaussian(rng), gaussian(rng), gaussian(rng));
  } while (!(v.norm() > 1e-9));
  return v.normalized();
}

// Uniform on SO(3): a normalized 4-D isotropic Gaussian is a uniform unit quaternion.
Eigen::Quaterniond randomRotation(std::mt19937_64& rng) {
  Eigen::Vector4d v;
  do {
    v = Eigen::Vector4d(gaussian(rng), gaussian(rng), gaussian(rng), gaussian(rng));
  } while (!(v.norm() > 1e-9));
  v.normalize();
  return Eigen::Quaterniond(v[0], v[1], v[2], v[3]);
}

Status checkConfig(const MeshQuery& cad, const SyntheticScanConfig& config) {
  if (!cad.status().ok()) {
    return Status::failure(cad.status().code,
                           "synthetic scan: unusable CAD: " + cad.status().message);
  }
  std::vector<std::string> problems;
  if (config.points == 0) {
    problems.push_back("points is 0");
  }
  const auto check = [&problems](double value, const char* name) {
    if (!std::isfinite(value) || value < 0.0) {
      problems.push_back(std::string(name) + " = " + std::to_string(value) +
                         " is not a finite value >= 0");
    }
  };
  check(config.noise_ratio, "noise_ratio");
  check(config.outlier_fraction, "outlier_fraction");
  check(config.min_translation_ratio, "min_translation_ratio");
  check(config.max_translation_ratio, "max_translation_ratio");
  if (config.min_translation_ratio > config.max_translation_ratio) {
    problems.push_back("min_translation_ratio " + std::to_string(config.min_translation_ratio) +
                       " > max_translation_ratio " + std::to_string(config.max_translation_ratio));
  }
  if (!problems.empty()) {
    return Status::failure(StatusCode::kInvalidInput, "synthetic scan: " + joinMessages(problems));
  }
  return Status::success();
}

// Area-weighted surface sampler over the faces of a mesh.
class SurfaceSampler {
 public:
  explicit SurfaceSampler(const TriangleMesh& mesh) : mesh_(mesh) {
    cumulative_.reserve(mesh.faces.size());
    double total = 0.0;
    for (const auto& f : mesh.faces) {
      total += triangleArea(mesh.vertices, f);
      cumulative_.push_back(total);
    }
  }

  // A point uniform by area, and the face it lies on.
  Eigen::Vector3d sample(std::mt19937_64& rng, std::size_t& face) const {
    const double pick = uniform01(rng) * cumulative_.back();
    // upper_bound skips zero-area faces (their cumulative value equals the previous one).
    face = static_cast<std::size_t>(
        std::upper_bound(cumulative_.begin(), cumulative_.end() - 1, pick) - cumulative_.begin());
    const Eigen::Vector3i& f = mesh_.faces[face];
    const double r1 = std::sqrt(uniform01(rng));
    const double r2 = uniform01(rng);
    return (1.0 - r1) * vertex(f[0]) + r1 * (1.0 - r2) * vertex(f[1]) + r1 * r2 * vertex(f[2]);
  }

 private:
  const Eigen::Vector3d& vertex(int index) const {
    return mesh_.vertices[static_cast<std::size_t>(index)];
  }

  const TriangleMesh& mesh_;
  std::vector<double> cumulative_;
};

}  // namespace

SyntheticScan makeSyntheticScan(const MeshQuery& cad, const SyntheticScanConfig& config) {
  SyntheticScan result;
  result.status = checkConfig(cad, config);
  if (!result.status.ok()) {
    return result;
  }
  const TriangleMesh& mesh = cad.mesh();
  const double diagonal = computeBoundingBox(mesh.vertices).diagonal();
  std::mt19937_64 rng(config.seed);

  // Pose and view first, so they depend on the seed only (not on points, noise, ...).
  const Eigen::Quaterniond rotation = randomRotation(rng);
  const Eigen::Vector3d translation_direction = randomUnitVector(rng);
  const double translation_length =
      diagonal * (config.min_translation_ratio +
                  (config.max_translation_ratio - config.min_translation_ratio) * uniform01(rng));
  const Eigen::Vector3d view = randomUnitVector(rng);
  Eigen::Isometry3d T_scan_cad = Eigen::Isometry3d::Identity();
  T_scan_cad.linear() = rotation.toRotationMatrix();
  T_scan_cad.translation() = translation_length * translation_direction;

  // Surface points (CAD frame). Partial views draw candidates in rounds, sized by the
  // acceptance rate seen so far, and keep those facing the sensor and not occluded.
  const SurfaceSampler sampler(mesh);
  Points points;
  Points normals;
  points.reserve(config.points);
  normals.reserve(config.points);
  std::size_t drawn = 0;
  for (int round = 0; round < kMaxRounds && points.size() < config.points; ++round) {
    const std::size_t missing = config.points - points.size();
    std::size_t batch = missing;
    if (config.partial && drawn > 0) {
      const double acceptance =
          std::max(static_cast<double>(points.size()) / static_cast<double>(drawn), 0.01);
      batch = static_cast<std::size_t>(1.1 * static_cast<double>(missing) / acceptance) + 16;
    }
    Points candidates(batch);
    std::vector<std::size_t> faces(batch);
    for (std::size_t i = 0; i < batch; ++i) {
      candidates[i] = sampler.sample(rng, faces[i]);
    }
    drawn += batch;
    std::vector<char> keep(batch, 1);
    if (config.partial) {
      const double offset = kRayOffsetRatio * diagonal;
      const auto count = static_cast<long long>(batch);
#pragma omp parallel for schedule(dynamic, 256)
      for (long long i = 0; i < count; ++i) {
        const auto k = static_cast<std::size_t>(i);
        keep[k] = mesh.face_normals[faces[k]].dot(view) > kFacingThreshold &&
                  !cad.castRay(candidates[k] + offset * view, view, 0.0).hit;
      }
    }
    for (std::size_t i = 0; i < batch && points.size() < config.points; ++i) {
      if (keep[i] != 0) {
        points.push_back(candidates[i]);
        normals.push_back(mesh.face_normals[faces[i]]);
      }
    }
    if (!config.partial) {
      break;  // every candidate is kept: one round is exact
    }
  }
  if (points.empty()) {
    result.status = Status::failure(StatusCode::kDegenerateInput,
                                    "synthetic scan: no surface point is visible from the view "
                                    "direction after " +
                                        std::to_string(drawn) + " samples");
    return result;
  }

  // Noise along the normal, then outliers uniform in the grown box of the noisy points.
  const double sigma = config.noise_ratio * diagonal;
  if (sigma > 0.0) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      points[i] += sigma * gaussian(rng) * normals[i];
    }
  }
  const auto outliers = static_cast<std::size_t>(
      std::llround(config.outlier_fraction * static_cast<double>(points.size())));
  if (outliers > 0) {
    const BoundingBox box = computeBoundingBox(points);
    const Eigen::Vector3d low = box.min - kOutlierBoxMargin * box.extent();
    const Eigen::Vector3d size = (1.0 + 2.0 * kOutlierBoxMargin) * box.extent();
    for (std::size_t i = 0; i < outliers; ++i) {
      const double x = uniform01(rng);
      const double y = uniform01(rng);
      const double z = uniform01(rng);
      points.push_back(low + Eigen::Vector3d(x, y, z).cwiseProduct(size));
      // A random unit normal rather than none, so that normal-using stages see them too.
      normals.push_back(randomUnitVector(rng));
    }
  }

  // Into the scan frame.
  result.scan.points.reserve(points.size());
  result.scan.normals.reserve(normals.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    result.scan.points.push_back(T_scan_cad * points[i]);
    result.scan.normals.push_back((T_scan_cad.linear() * normals[i]).normalized());
  }
  result.T_cad_scan = T_scan_cad.inverse();
  result.view_direction = config.partial ? view : Eigen::Vector3d::Zero();
  result.outliers = outliers;
  return result;
}

std::size_t pressDefect(const MeshQuery& cad, const SurfaceDefect& defect, SyntheticScan* scan) {
  const Eigen::Vector3d facing = cad.closest(defect.centre).normal;
  const Eigen::Matrix3d R_scan_cad = scan->T_cad_scan.linear().transpose();
  const std::size_t surface = scan->scan.points.size() - scan->outliers;
  std::size_t moved = 0;
  for (std::size_t i = 0; i < surface; ++i) {
    Eigen::Vector3d& p = scan->scan.points[i];
    const ClosestPoint on = cad.closest(scan->T_cad_scan * p);
    const double displacement = defectDisplacement(defect, on.point);
    if (displacement != 0.0 && on.normal.dot(facing) > kDefectFacingCos) {
      p += displacement * (R_scan_cad * on.normal);
      ++moved;
    }
  }
  return moved;
}

}  // namespace freeform_inspection
