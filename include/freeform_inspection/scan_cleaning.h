// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/types.h"

/// @file scan_cleaning.h
/// First stage: make the scan safe for every later stage (finite points, sane size, units that
/// match the model, a shape that can fix a pose) or say why it is not.

namespace freeform_inspection {

/// Checks on the incoming scan before any geometry is computed.
struct InputConfig {
  std::size_t max_points = 5000000;   ///< larger scans are refused (memory and latency bound)
  std::size_t min_points = 3;         ///< a rigid pose needs at least three points
  double max_extent_ratio = 50.0;     ///< scan/CAD diagonal ratio beyond which units are suspect
  double min_thickness_ratio = 1e-3;  ///< principal spread (2nd or 3rd over 1st) below which the
                                      ///< scan is collinear or planar and cannot fix a pose
  /// [m] the box a scan is cropped to before anything else, in the frame of
  /// `crop_frame_from_scan`: {x_min, y_min, z_min, x_max, y_max, z_max}; empty keeps every
  /// point. For what the scanner always sees around the part (fixture, clamps, a gripper).
  std::vector<double> crop_box;
  /// Takes scan coordinates into the frame the crop box is given in. Not a configuration key:
  /// identity (the box is in the scan's own frame), or set per scan by the caller (the node: the
  /// scan's pose in ~fixed_frame, so a box around a fixture holds wherever the robot carries the
  /// scanner).
  Eigen::Isometry3d crop_frame_from_scan = Eigen::Isometry3d::Identity();
};

/// @brief The points of `scan` outside `box` ({x_min, y_min, z_min, x_max, y_max, z_max} in the
/// frame that `box_from_scan` takes the scan into) made NaN, so cleanScan() drops them with the
/// faces through them and an organized scan keeps its grid; `cropped` counts them (NaN points
/// already there are not). An empty box changes nothing.
Scan cropToBox(const Scan& scan,
               const std::vector<double>& box,
               const Eigen::Isometry3d& box_from_scan,
               std::size_t* cropped);

/// Result of cleaning.
struct CleanScanResult {
  Status status;               ///< kInvalidInput, kDegenerateInput or kUnitsMismatch on refusal
  Scan scan;                   ///< finite points (faces re-indexed, normals kept)
  std::size_t non_finite = 0;  ///< points removed because a coordinate was NaN or inf
};

/// @brief Removes non-finite points and refuses scans that are empty, too large, too small,
/// collinear, planar, or whose extent differs from the model's by a unit-like factor.
/// @param model_bounds bounding box of the CAD model in metres.
CleanScanResult cleanScan(const Scan& scan,
                          const BoundingBox& model_bounds,
                          const InputConfig& config);

}  // namespace freeform_inspection
