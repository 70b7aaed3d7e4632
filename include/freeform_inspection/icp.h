// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/chord_error.h"
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
  /// Points with outward normals pair only with CAD faces turned less than this from them
  /// [deg]: a noisy point on a wall thinner than its noise is often nearer the wall's far side,
  /// and pairs made there pull the pose into the wall. 180 pairs every point with the nearest
  /// face whatever its normal.
  double facing_tolerance_deg = 80.0;
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
  /// CurvedSurface::estimate: the share of the curve the scan follows, and its standard error
  double curve_share = 0.0;
  double curve_share_error = 0.0;

  /// True when T_cad_scan is a refined pose: converged, or stopped at the iteration limit.
  bool usable() const { return status.ok() || status.code == StatusCode::kNotConverged; }
};

/// @brief The fit of `scan_points` at `pose` without moving it: robust σ of the residuals to the
/// closest CAD points (up to max_cutoff_ratio · L away), the inlier distance (3σ, bounded), the
/// inliers' RMS and their share of the points used (at most max_points, evenly spread).
/// @param scan_normals outward unit normals of the points (scan frame), or empty: given, each
/// point's closest CAD point is sought among the faces that face its way
/// (IcpConfig::facing_tolerance_deg), as in refinePose().
IcpResult measureFit(const MeshQuery& cad,
                     const Points& scan_points,
                     const Eigen::Isometry3d& pose,
                     double cad_diagonal,
                     const IcpConfig& config,
                     const Points& scan_normals = Points(),
                     const CurvedSurface& curved = CurvedSurface());

/// A rigid motion that a fit constrains little: the points slide along the surface instead of
/// leaving it (a prismatic part along its axis, a tube turned about it).
struct WeakMotion {
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();     ///< [rad per metre of motion]
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  ///< [m per metre of motion]
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();       ///< [m] of the turn, CAD frame
  /// Mean squared displacement of the points along their surface normal per unit of motion: 1
  /// for a motion straight off a plane, 0 for one that no point's surface resists.
  double stiffness = 0.0;

  /// @brief The motion taken `distance` far [m]: the points move about that much (RMS).
  Eigen::Isometry3d by(double distance) const;
};

/// @brief The `count` least constrained motions of `points` at `pose`: eigenvectors of the
/// point-to-plane normal matrix (the matrix ICP's step solves with), over the points within
/// `max_distance` of the CAD, turns scaled by the points' RMS distance from their centroid so
/// that a turn and a shift that move the points equally far compare. Weakest first; empty when
/// fewer than six points reach the CAD.
std::vector<WeakMotion> weakestMotions(const MeshQuery& cad,
                                       const Points& points,
                                       const Eigen::Isometry3d& pose,
                                       double max_distance,
                                       int count);

/// @brief Refines `initial` by ICP.
/// @param initial_cutoff [m] cut-off of the first iteration (the global stage's accuracy)
/// @param scan_normals outward unit normals of the points (scan frame, one per point), or
/// empty: given, a point pairs only with CAD faces that face its way
/// (IcpConfig::facing_tolerance_deg).
IcpResult refinePose(const MeshQuery& cad,
                     const Points& scan_points,
                     const Eigen::Isometry3d& initial,
                     double initial_cutoff,
                     double cad_diagonal,
                     const IcpConfig& config,
                     const Points& scan_normals = Points(),
                     const CurvedSurface& curved = CurvedSurface());

/// A least-squares share of the curve in a fit's residuals, and its standard error.
struct CurveShare {
  double share = 0.0;
  double error = 0.0;
};

/// @brief How much of the bulges of the curve the CAD's faces stand for (chord_error.h) the
/// signed residuals of `scan_points` at `pose` show, without moving the pose: over the points
/// within `band` [m] plus the largest bulge of the faces. The pose, fitted to the faces, has taken
/// up part of the bulges, so a scan of the curve reads below 1 here (a pump cover's views:
/// 0.28-0.33); a scan made from the mesh itself reads 0. A cheap test of whether ICP should fit
/// the share with the pose.
CurveShare curveShareAt(const MeshQuery& cad,
                        const ChordError& chord,
                        const Points& scan_points,
                        const Eigen::Isometry3d& pose,
                        double band,
                        const IcpConfig& config,
                        const Points& scan_normals = Points());

}  // namespace freeform_inspection
