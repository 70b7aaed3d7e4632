// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <Eigen/Geometry>

// Pose errors the benchmarks report against the truth (issue 4's success rule uses them).
namespace freeform_inspection::bench {

/// Angle [deg] of the rotation that takes `a`'s orientation to `b`'s.
inline double rotationErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 /
         3.14159265358979323846;
}

}  // namespace freeform_inspection::bench
