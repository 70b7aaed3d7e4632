// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "freeform_inspection/deviation.h"
#include "freeform_inspection/types.h"

/// @file defects.h
/// Defect regions: out-of-tolerance scan points joined into connected regions on the scan
/// surface (the scan's triangles, or its neighbourhood graph for a cloud), one sign per region.

namespace freeform_inspection {

/// How out-of-tolerance points become defect regions.
struct DefectConfig {
  int min_points = 10;  ///< smaller regions are noise, not defects [points]
  /// Regions of less area are not defects either: the smallest flaw the drawing or the customer
  /// counts, whatever the scan's density [m²]. 0 leaves the size to min_points alone.
  double min_area = 0.0;
  /// Clouds: two points are neighbours within this many median scan spacings. 4 gives a
  /// random sampling ~11 neighbours per point, well above the ~4.5 where a random graph falls
  /// apart into pieces (2.5 split one dent into a dozen regions).
  double neighbour_spacings = 4.0;
};

/// @brief One message per invalid field; empty when valid.
std::vector<std::string> validate(const DefectConfig& config);

/// A connected out-of-tolerance region of one sign.
struct DefectRegion {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< [m] CAD frame
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero();  ///< [m] CAD frame
  Eigen::Vector3d bbox_max = Eigen::Vector3d::Zero();  ///< [m] CAD frame
  std::size_t points = 0;                              ///< scan points in the region
  double area = 0.0;                                   ///< [m^2] approximate surface area
  double peak = 0.0;                                   ///< [m] signed, largest magnitude
  double mean = 0.0;                                   ///< [m] mean signed deviation
  int sign = 0;  ///< +1 excess material (bump), -1 missing material (dent)
  /// The named region (regions.h) it lies in, -1 for the rest of the part: points of different
  /// regions are judged against different bands and never join one defect.
  int region = -1;
  /// [m] the largest chord error (chord_error.h) of the CAD faces the region lies on: where it
  /// is a good share of the peak, the region may be the CAD's tessellation, not the part.
  double cad_chord_error = 0.0;
};

/// Regions, largest |peak| first, and for each point the region it belongs to (-1 for none).
struct DefectResult {
  std::vector<DefectRegion> regions;
  std::vector<int> point_region;
};

/// The scan surface's connectivity as findDefects() reads it, kept for several bands judged on
/// the same points (the guard bands of the verdict judge three): a cloud's kd-tree, median
/// spacing and neighbour table are built once, on first need. Holds references to the points
/// and faces, which must outlive it. Not thread-safe.
class DefectNeighbourhood {
 public:
  /// @param points_cad scan points in the CAD frame.
  /// @param faces the scan's triangles (its connectivity), or empty for a cloud.
  DefectNeighbourhood(const Points& points_cad, const Triangles& faces);
  ~DefectNeighbourhood();
  DefectNeighbourhood(const DefectNeighbourhood&) = delete;
  DefectNeighbourhood& operator=(const DefectNeighbourhood&) = delete;

 private:
  struct Impl;
  friend DefectResult findDefects(DefectNeighbourhood& neighbourhood,
                                  const std::vector<float>& deviation,
                                  const ToleranceBands& tolerance,
                                  const DefectConfig& config);
  std::unique_ptr<Impl> impl_;
};

/// @brief Clusters the out-of-tolerance points of a deviation map, each point judged against
/// its own band; points join only points of their region.
/// @param deviation signed deviation per point of the neighbourhood [m], NaN for unmatched
/// points (never defects).
DefectResult findDefects(DefectNeighbourhood& neighbourhood,
                         const std::vector<float>& deviation,
                         const ToleranceBands& tolerance,
                         const DefectConfig& config);

/// @brief findDefects() for one band: the neighbourhood built for this call alone.
/// @param points_cad scan points in the CAD frame.
/// @param faces the scan's triangles (its connectivity), or empty for a cloud.
DefectResult findDefects(const Points& points_cad,
                         const Triangles& faces,
                         const std::vector<float>& deviation,
                         const ToleranceBands& tolerance,
                         const DefectConfig& config);

}  // namespace freeform_inspection
