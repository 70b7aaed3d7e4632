// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/scan_cleaning.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include <Eigen/Eigenvalues>

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

Scan keepFinite(const Scan& scan, std::size_t* removed) {
  Scan out;
  std::vector<int> new_index(scan.points.size(), -1);
  const bool with_normals = scan.normals.size() == scan.points.size();
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    if (!scan.points[i].allFinite()) {
      continue;
    }
    new_index[i] = static_cast<int>(out.points.size());
    out.points.push_back(scan.points[i]);
    if (with_normals) {
      out.normals.push_back(scan.normals[i]);
    }
  }
  for (const auto& f : scan.faces) {
    const Eigen::Vector3i g(new_index[static_cast<std::size_t>(f[0])],
                            new_index[static_cast<std::size_t>(f[1])],
                            new_index[static_cast<std::size_t>(f[2])]);
    if (g.minCoeff() >= 0) {
      out.faces.push_back(g);
    }
  }
  *removed = scan.points.size() - out.points.size();
  return out;
}

bool facesInRange(const Scan& scan) {
  const auto n = static_cast<int>(scan.points.size());
  for (const auto& f : scan.faces) {
    if (f.minCoeff() < 0 || f.maxCoeff() >= n) {
      return false;
    }
  }
  return true;
}

// Square roots of the covariance eigenvalues, largest first: the spread along each axis.
Eigen::Vector3d principalSpread(const Points& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) {
    mean += p;
  }
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) {
    covariance += (p - mean) * (p - mean).transpose();
  }
  covariance /= static_cast<double>(points.size());
  const Eigen::Vector3d eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvalues();
  return eigenvalues.reverse().cwiseMax(0.0).cwiseSqrt();
}

std::string number(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

Status checkExtent(const Points& points,
                   const BoundingBox& model_bounds,
                   const InputConfig& config) {
  const double scan_diagonal = computeBoundingBox(points).diagonal();
  const double model_diagonal = model_bounds.diagonal();
  const double ratio = scan_diagonal / model_diagonal;
  if (ratio > config.max_extent_ratio || ratio < 1.0 / config.max_extent_ratio) {
    return Status::failure(
        StatusCode::kUnitsMismatch,
        "scan extent " + number(scan_diagonal) + " m is " + number(ratio) +
            " times the CAD extent " + number(model_diagonal) +
            " m: check the units of the scan and of the CAD (millimetres need scale 0.001)");
  }
  return Status::success();
}

Status checkShape(const Points& points, const InputConfig& config) {
  const Eigen::Vector3d spread = principalSpread(points);
  if (spread[0] <= 0.0 || spread[1] < config.min_thickness_ratio * spread[0]) {
    return Status::failure(StatusCode::kDegenerateInput,
                           "scan is collinear (principal spreads " + number(spread[0]) + ", " +
                               number(spread[1]) + " m): it cannot fix a pose");
  }
  if (spread[2] < config.min_thickness_ratio * spread[0]) {
    return Status::failure(StatusCode::kDegenerateInput,
                           "scan is planar (thickness " + number(spread[2]) +
                               " m over a spread of " + number(spread[0]) +
                               " m): it cannot fix a pose");
  }
  return Status::success();
}

}  // namespace

Scan cropToBox(const Scan& scan,
               const std::vector<double>& box,
               const Eigen::Isometry3d& box_from_scan,
               std::size_t* cropped) {
  *cropped = 0;
  if (box.size() != 6) {
    return scan;
  }
  const Eigen::Vector3d low(box[0], box[1], box[2]);
  const Eigen::Vector3d high(box[3], box[4], box[5]);
  Scan inside = scan;
  for (Eigen::Vector3d& p : inside.points) {
    const Eigen::Vector3d in_box = box_from_scan * p;
    if (p.allFinite() &&
        !((in_box.array() >= low.array()).all() && (in_box.array() <= high.array()).all())) {
      p = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
      ++*cropped;
    }
  }
  return inside;
}

CleanScanResult cleanScan(const Scan& scan,
                          const BoundingBox& model_bounds,
                          const InputConfig& config) {
  CleanScanResult result;
  if (!facesInRange(scan)) {
    result.status = Status::failure(StatusCode::kInvalidInput, "scan face index out of range");
    return result;
  }
  if (scan.points.size() > config.max_points) {
    result.status = Status::failure(
        StatusCode::kInvalidInput,
        "scan has " + std::to_string(scan.points.size()) +
            " points, more than input.max_points = " + std::to_string(config.max_points));
    return result;
  }
  result.scan = keepFinite(scan, &result.non_finite);
  const std::size_t n = result.scan.points.size();
  if (n == 0) {
    result.status = Status::failure(
        StatusCode::kInvalidInput,
        "scan has no finite points (" + std::to_string(scan.points.size()) + " received)");
  } else if (n < config.min_points) {
    result.status = Status::failure(StatusCode::kDegenerateInput,
                                    "scan has " + std::to_string(n) +
                                        " finite points; registration needs at least " +
                                        std::to_string(config.min_points));
  } else {
    result.status = checkShape(result.scan.points, config);
    if (result.status.ok()) {
      result.status = checkExtent(result.scan.points, model_bounds, config);
    }
  }
  return result;
}

}  // namespace freeform_inspection
