// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/types.h"

// The Stanford "dragon_stand" turntable series (Cyberware 3030MS, 15 views 24° apart, ground
// truth in dragonStandRight.conf), read for the benchmarks that register its real range scans
// (dragon_eval, pcl_compare --dragon). There is no CAD of the dragon: a view plays the CAD.
namespace freeform_inspection::bench {

/// One range scan: its grid (NaN where nothing was measured) in the scanner's frame.
struct RangeScan {
  Points grid;
  int width = 0;
  int height = 0;
};

/// The Cyberware ASCII PLY: `element vertex` (x y z), then `element range_grid` with one line
/// per grid cell, "0" or "1 <vertex>", row-major with num_cols columns. False, with `error`,
/// for anything else.
bool readRangeScan(const std::string& path, RangeScan* scan, std::string* error);

/// "bmesh <file> tx ty tz qi qj qk qr" lines: p_common = q̄ · p_scan + t, keyed by file name.
std::map<std::string, Eigen::Isometry3d> readDragonPoses(const std::string& conf_path);

/// The 15 views' file names, 0° to 336°.
std::vector<std::string> dragonViewNames();

/// The view as a CAD: its grid triangulated, compacted to the measured points, moved by `pose`,
/// faces turned away from the surface's centroid (the front of a view is convex-ish towards the
/// scanner; the grid's own +z convention does not hold in this scanner's frame).
TriangleMesh viewAsMesh(const RangeScan& scan, const Eigen::Isometry3d& pose);

/// The measured points of the grid, in the scanner's frame.
Points measuredPoints(const RangeScan& scan);

/// One registration case: view `cad_view` (moved into the common frame) as the CAD and the view
/// `step` further on as the scan, bare points in its own frame, with the true scan → CAD pose.
struct DragonPair {
  std::string cad_view;
  std::string scan_view;
  TriangleMesh cad;
  Points scan;
  Eigen::Isometry3d T_cad_scan = Eigen::Isometry3d::Identity();
};

/// Every view paired with the one `step` further on (15 pairs). False, with `error`, when a file
/// or pose of `dir` is missing or unreadable.
bool readDragonPairs(const std::string& dir,
                     int step,
                     std::vector<DragonPair>* pairs,
                     std::string* error);

}  // namespace freeform_inspection::bench
