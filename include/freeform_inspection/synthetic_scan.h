// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>

#include <Eigen/Geometry>

#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/surface_defect.h"
#include "freeform_inspection/types.h"

/// @file synthetic_scan.h
/// The case generator: a scan of a CAD mesh at a random rigid pose, full or partial, with noise
/// and outliers, and the ground truth. Tests and benchmarks use it to measure registration.

namespace freeform_inspection {

/// What kind of scan to make. Lengths relative to the mesh's bounding-box diagonal L.
struct SyntheticScanConfig {
  /// surface points before outliers; a partial view may deliver fewer when little is visible
  std::size_t points = 30000;
  bool partial = false;      ///< true: only what a sensor sees from one random direction
  double noise_ratio = 0.0;  ///< σ of Gaussian noise along the normal, × L
  /// outliers added, × the surface points generated (uniform in their bounding box grown by
  /// 10 % per side; each with a random unit normal)
  double outlier_fraction = 0.0;
  double min_translation_ratio = 0.5;  ///< |t| of the random pose is uniform in [min, max] × L
  double max_translation_ratio = 1.5;
  std::uint64_t seed = 1;  ///< everything is deterministic for a seed
};

/// A generated scan and its truth.
struct SyntheticScan {
  Status status;  ///< e.g. mesh without faces
  Scan scan;      ///< points (and unit normals) in the scan frame [m]
  Eigen::Isometry3d T_cad_scan = Eigen::Isometry3d::Identity();  ///< truth: scan → CAD
  /// CAD frame, unit, towards the sensor (partial views; zero for a full scan)
  Eigen::Vector3d view_direction = Eigen::Vector3d::Zero();
  std::size_t outliers = 0;  ///< how many of the points are outliers (the last ones)
};

/// @brief Makes one case: samples the surface uniformly by area, keeps (partial) the samples
/// visible from a uniformly random direction (facing it and not occluded, by ray casting),
/// adds noise along the normal and outliers, then moves everything by a uniformly random
/// rotation and a translation of random direction and length.
SyntheticScan makeSyntheticScan(const MeshQuery& cad, const SyntheticScanConfig& config);

/// @brief Presses `defect` (CAD frame) into a generated scan: each surface point (not the
/// outliers) moves by defectDisplacement() along the CAD normal at its closest point, where
/// that normal is within 60° of the normal at the defect's centre, so the far side of a wall
/// thinner than the defect stays where it was. The scan's normals are left as they were.
/// @return how many points moved.
std::size_t pressDefect(const MeshQuery& cad, const SurfaceDefect& defect, SyntheticScan* scan);

}  // namespace freeform_inspection
