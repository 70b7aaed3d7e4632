// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cmath>

#include <Eigen/Geometry>

#include "freeform_inspection/pose_uncertainty.h"

// Pose errors the benchmarks report against the truth (issue 4's success rule uses them).
namespace freeform_inspection::bench {

/// Angle [deg] of the rotation that takes `a`'s orientation to `b`'s.
inline double rotationErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 /
         3.14159265358979323846;
}

/// The errors `uncertainty` predicts for the pose `T_cad_scan`: RMS of the rotation angle [deg],
/// and RMS of the error at `point_scan` (a scan point, scan frame) [m]. Read from the covariance
/// of the part's pose in the scan frame, the way a ROS user would read it.
struct PredictedError {
  double rotation_deg = 0.0;
  double at_point = 0.0;
};

inline PredictedError predictedError(const PoseUncertainty& uncertainty,
                                     const Eigen::Isometry3d& T_cad_scan,
                                     const Eigen::Vector3d& point_scan) {
  const Eigen::Matrix<double, 6, 6>& c = uncertainty.covariance;
  // The point moves by δp + δθ × (s − p), p the part origin in the scan frame.
  const Eigen::Vector3d arm = point_scan - T_cad_scan.inverse().translation();
  Eigen::Matrix3d cross;
  cross << 0.0, -arm.z(), arm.y(), arm.z(), 0.0, -arm.x(), -arm.y(), arm.x(), 0.0;
  Eigen::Matrix<double, 3, 6> map;
  map << Eigen::Matrix3d::Identity(), -cross;
  return {std::sqrt(c.bottomRightCorner<3, 3>().trace()) * 180.0 / 3.14159265358979323846,
          std::sqrt((map * c * map.transpose()).trace())};
}

}  // namespace freeform_inspection::bench
