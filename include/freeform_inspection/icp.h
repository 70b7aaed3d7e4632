// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/types.h"

/// @file icp.h
/// Local registration (paper §2.6, §3.6.2): ICP from the global pose, with closest points on the
/// exact CAD triangles. Point-to-point (the paper) or point-to-plane (default, converges in far
/// fewer iterations on smooth parts). Trimmed: pairs farther than a cut-off are left out, and the
/// cut-off follows the measured residual (3 robust σ), so partial scans, outliers and defects do
/// not pull the pose while plain sensor noise does not bias it. Stops when the mean squared
/// error changes by less than ε between iterations (eq. 15).

namespace freeform_inspection {

/// ICP settings. Lengths are ratios of the CAD diagonal L.
struct IcpConfig {
  bool point_to_plane = true;  ///< false: the paper's point-to-point
  int max_iterations = 60;
  double convergence = 1e-5;  ///< eq. 15: stop when |e_h − e_{h+1}| < this × e_h
  /// or when the error rose while the step moved no point by this × the residual's robust σ
  /// (a noisy scan's error jitters once the pose has settled and never meets eq. 15)
  double still_fraction = 0.01;
  double sigma_multiple = 3.0;     ///< cut-off = this × robust σ of the residuals
  double min_cutoff_ratio = 1e-5;  ///< cut-off never below this × L (numerical floor)
  double max_cutoff_ratio = 0.05;  ///< nor above this × L (the inlier ceiling for fitness)
  std::size_t max_points = 20000;  ///< points used per iteration (evenly spread subset)
};

/// @brief One message per invalid field; empty when valid.
std::vector<std::string> validate(const IcpConfig& config);

/// Refined pose and its fit.
struct IcpResult {
  Status status;
  Eigen::Isometry3d T_cad_scan = Eigen::Isometry3d::Identity();
  int iterations = 0;
  bool converged = false;
  double sigma = 0.0;            ///< [m] robust σ of the final residuals (1.4826 · MAD)
  double inlier_distance = 0.0;  ///< [m] final cut-off
  double rmse = 0.0;             ///< [m] RMS distance of the inliers
  double fitness = 0.0;          ///< share of the used points within inlier_distance

  /// True when T_cad_scan is a refined pose: converged, or stopped at the iteration limit.
  bool usable() const { return status.ok() || status.code == StatusCode::kNotConverged; }
};

/// @brief The fit of `scan_points` at `pose` without moving it: robust σ of the residuals to the
/// closest CAD points (up to max_cutoff_ratio · L away), the inlier distance (3σ, bounded), the
/// inliers' RMS and their share of the points used (at most max_points, evenly spread).
IcpResult measureFit(const MeshQuery& cad,
                     const Points& scan_points,
                     const Eigen::Isometry3d& pose,
                     double cad_diagonal,
                     const IcpConfig& config);

/// @brief Refines `initial` by ICP.
/// @param initial_cutoff [m] cut-off of the first iteration (the global stage's accuracy)
IcpResult refinePose(const MeshQuery& cad,
                     const Points& scan_points,
                     const Eigen::Isometry3d& initial,
                     double initial_cutoff,
                     double cad_diagonal,
                     const IcpConfig& config);

}  // namespace freeform_inspection
