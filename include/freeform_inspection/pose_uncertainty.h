// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/types.h"

/// @file pose_uncertainty.h
/// How far the scan's noise leaves the registered pose free to move: the covariance of the
/// point-to-plane fit at the final pose, σ² (JᵀJ)⁻¹, over the points within the inlier distance,
/// with σ the fit's robust residual (docs/registration.md, "Pose uncertainty"). It assumes
/// independent errors along the normals: a form error of the part or a scanner's correlated
/// error adds to it, so it is a lower bound on the pose's error, and the part of it the noise
/// alone explains.

namespace freeform_inspection {

/// Covariance of a registered pose.
struct PoseUncertainty {
  bool known = false;  ///< false with fewer than six inliers or no residual σ
  /// The part's pose in the scan frame (the inverse of T_cad_scan), in the order of
  /// geometry_msgs/PoseWithCovariance: the part frame origin's position x, y, z [m²] and small
  /// turns about the scan frame's x, y, z axes [rad²]. Row-major when flattened.
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  /// [deg] 1σ of the turn about the least constrained axis (through the inliers' centroid).
  double rotation_deg = std::numeric_limits<double>::quiet_NaN();
  /// [m] 1σ of the inliers' centroid along its least constrained direction.
  double translation = std::numeric_limits<double>::quiet_NaN();
  /// False when some motion is not held by the data at all (a sphere's turns, a plane's
  /// slides): its variance is then capped at a half turn or π CAD diagonals.
  bool constrained = false;
  std::size_t points = 0;  ///< inliers the covariance comes from
};

/// @brief The covariance of `T_cad_scan` from the deviation map at that pose.
/// @param points_cad scan points in the CAD frame (at `T_cad_scan`)
/// @param cad_normals outward CAD normal at each point's closest point (zero where unmatched)
/// @param deviation signed distance of each point to the CAD (NaN where unmatched)
/// @param inlier_distance [m] points with |deviation| above it are left out (defects, outliers)
/// @param sigma [m] robust σ of the fit's residuals
/// @param cad_diagonal [m] scales translations against turns in the cap of free motions
PoseUncertainty estimatePoseUncertainty(const Points& points_cad,
                                        const Points& cad_normals,
                                        const std::vector<float>& deviation,
                                        const Eigen::Isometry3d& T_cad_scan,
                                        double inlier_distance,
                                        double sigma,
                                        double cad_diagonal);

/// RMS errors a pose covariance predicts.
struct PredictedSpread {
  double rotation = 0.0;  ///< [rad] RMS of the rotation angle
  double at_point = 0.0;  ///< [m] RMS of the error at the point asked for
};

/// @brief What `uncertainty` predicts for the pose `T_cad_scan`, read from the covariance of the
/// part's pose in the scan frame as a ROS consumer reads it: a scan point s moves by
/// δp + δθ × (s − p), p the part origin in the scan frame.
/// @param point_scan [m] a point in the scan frame (e.g. the scan's centroid)
PredictedSpread predictedSpread(const PoseUncertainty& uncertainty,
                                const Eigen::Isometry3d& T_cad_scan,
                                const Eigen::Vector3d& point_scan);

}  // namespace freeform_inspection
