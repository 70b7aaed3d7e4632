// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "freeform_inspection/deviation.h"
#include "freeform_inspection/types.h"

/// @file regions.h
/// Named regions of the CAD surface (docs/inspection.md, "Regions"): parts of the surface with a
/// tolerance band of their own (an airfoil at ±0.05 mm, its root at ±0.2 mm) or left out of the
/// verdict (a face machined later, where the fixture clamps). A region is a union of boxes in the
/// CAD frame; a place on the CAD surface belongs to the first region, in the order given, with a
/// box holding it. The rest of the surface is judged with the part's tolerance.

namespace freeform_inspection {

/// An axis-aligned box in the CAD frame [m].
struct RegionBox {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  bool contains(const Eigen::Vector3d& p) const {
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
  }
};

/// One named region and how it is judged.
struct RegionConfig {
  std::string name;
  std::vector<RegionBox> boxes;  ///< [m] CAD frame; the region is their union
  /// Its own band; when false, the part's (PipelineConfig::tolerance).
  bool has_tolerance = false;
  ToleranceConfig tolerance;
  /// False: its points are left out of the statistics, the defects and the verdict (they stay
  /// in the deviation map, measured).
  bool evaluate = true;
  /// False: its points are left out of the best fit (stock left for a later operation, a
  /// surface the fixture bends): after the registration the pose is refitted to the rest.
  bool align = true;
  /// NOT_EVALUATED (the region and the part) when the scan covers less of the region's CAD
  /// surface than this; 0: any view.
  double min_coverage = 0.0;
};

/// @brief One message per invalid field of each region (named by its name or position); empty
/// when valid. Names must be unique and non-empty, each region needs a box with min ≤ max.
std::vector<std::string> validate(const std::vector<RegionConfig>& regions);

/// Result of reading a regions file.
struct RegionsLoadResult {
  Status status;  ///< kInvalidInput naming every bad or unknown key
  std::vector<RegionConfig> regions;
};

/// @brief Reads regions from YAML: a top-level `regions:` list of maps with `name`, `boxes`
/// (a list of `{min: [x, y, z], max: [x, y, z]}`, metres in the CAD frame), optional
/// `tolerance: {upper, lower}`, `evaluate`, `align` and `min_coverage`. Unknown keys are errors, as
/// in the configuration file.
RegionsLoadResult parseRegions(const std::string& yaml_text);

/// @brief parseRegions() of a file; an unreadable file is kInvalidInput naming it.
RegionsLoadResult loadRegionsFile(const std::string& path);

/// @brief The region of each place (CAD frame): the index of the first region with a box
/// holding it, -1 for none (the rest of the part) or for a non-finite place.
std::vector<int> regionOf(const std::vector<RegionConfig>& regions, const Points& places);

/// @brief The band that applies to `region` (-1: the part's `part_tolerance`).
ToleranceConfig regionTolerance(const std::vector<RegionConfig>& regions,
                                int region,
                                const ToleranceConfig& part_tolerance);

/// @brief Each point's band: its region's (`region_of`, from regionOf()) or the part's.
ToleranceBands toleranceBands(const std::vector<RegionConfig>& regions,
                              std::vector<int> region_of,
                              const ToleranceConfig& part_tolerance);

}  // namespace freeform_inspection
