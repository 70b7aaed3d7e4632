// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/descriptor.h"
#include "freeform_inspection/types.h"

/// @file deviation.h
/// The signed deviation of a registered scan from the CAD surface, and its statistics.
/// Sign convention: positive = material outside the nominal surface (along the outward CAD
/// normal), negative = material missing. Lengths in metres.

namespace freeform_inspection {

class Model;

/// Tolerance band on the signed deviation.
struct ToleranceConfig {
  double upper = 1e-4;   ///< [m] largest allowed positive deviation (excess material)
  double lower = -1e-4;  ///< [m] most negative allowed deviation (missing material)
};

/// Tolerance bands that differ over the surface (named regions, regions.h): point i is judged
/// against `region_bands[region_of[i]]`, or against `part` where region_of[i] is -1 or
/// region_of is empty. Converts implicitly from one band for the whole part.
struct ToleranceBands {
  ToleranceBands(const ToleranceConfig& part_band) : part(part_band) {}  // NOLINT: one band
  ToleranceConfig part;
  std::vector<ToleranceConfig> region_bands;
  std::vector<int> region_of;  ///< per point: index into region_bands, -1 the part's band
  int regionAt(std::size_t i) const { return region_of.empty() ? -1 : region_of[i]; }
  const ToleranceConfig& at(std::size_t i) const {
    const int region = regionAt(i);
    return region < 0 ? part : region_bands[static_cast<std::size_t>(region)];
  }
};

/// How deviations are measured and summarised.
struct DeviationConfig {
  /// Points farther than this × CAD diagonal from the CAD are not part of it (fixture, floor,
  /// outliers): counted as unmatched, left out of the statistics.
  double max_distance_ratio = 0.05;
  /// A CAD vertex is covered when a scan point lies within this many surface-graph cells, or
  /// within 2.5 scan spacings when the scan is sparser than that.
  double coverage_distance_cells = 1.0;
  int histogram_bins = 40;  ///< bins of the deviation histogram
  /// Scans whose normals point out of the material (scanner normals, meshes, range images): a
  /// point is measured to the closest CAD surface turned less than this from its normal [deg],
  /// so a point of a thin wall dented or worn past its middle reads against its own side, not
  /// the far one. 180 measures every point to the closest surface whatever its way.
  double facing_tolerance_deg = 80.0;
};

/// @brief One message per invalid field; empty when valid.
std::vector<std::string> validate(const ToleranceConfig& config);
std::vector<std::string> validate(const DeviationConfig& config);

/// Per-point results, one entry per cleaned scan point, in the CAD frame. Unmatched points
/// (no CAD surface within reach, or beyond the border of an open CAD surface) have NaN
/// deviation.
struct DeviationMap {
  Points points;                       ///< [m] scan points in the CAD frame
  std::vector<float> deviation;        ///< [m] signed distance to the CAD surface, NaN unmatched
  std::vector<float> shape_deviation;  ///< mean_k |V_k(scan) - V_k(CAD)|, NaN where unknown
  std::vector<int> defect;             ///< index into InspectionResult::defects, -1 for none
  /// named region (regions.h, PipelineConfig::regions) of the point's closest CAD point, -1 the
  /// rest of the part or unmatched; empty when no region is named
  std::vector<int> region;

  std::size_t size() const { return points.size(); }
};

/// Statistics of the signed deviation over the evaluated (matched) scan points.
struct DeviationStatistics {
  std::size_t evaluated = 0;            ///< points with a CAD surface within reach
  std::size_t unmatched = 0;            ///< points too far from the CAD to be part of it
  std::size_t excluded = 0;             ///< points on regions left out of the verdict (regions.h)
  double mean = 0.0;                    ///< [m]
  double std = 0.0;                     ///< [m]
  double rms = 0.0;                     ///< [m]
  double min = 0.0;                     ///< [m]
  double max = 0.0;                     ///< [m]
  double p5 = 0.0;                      ///< [m]
  double p50 = 0.0;                     ///< [m]
  double p95 = 0.0;                     ///< [m]
  double in_tolerance_fraction = 0.0;   ///< share of evaluated points inside the band
  double coverage = 0.0;                ///< share of CAD area with scan points near it
  double shape_mean = 0.0;              ///< mean shape deviation (descriptor difference) [-]
  double shape_p95 = 0.0;               ///< 95th percentile of the shape deviation [-]
  std::vector<double> histogram_edges;  ///< [m] bin edges, one more than the counts
  std::vector<std::size_t> histogram_counts;  ///< points per bin (outer bins take the tails)
};

/// Where each point meets the CAD surface.
struct SurfaceDistances {
  std::vector<float> deviation;  ///< [m] signed distance, NaN for unmatched points
  Points normals;                ///< outward CAD normal at the closest point (zero: unmatched)
  std::vector<int> faces;        ///< CAD face holding the closest point, -1 unmatched
  Points closest;                ///< [m] the closest point on the CAD (NaN: unmatched)
};

/// @brief Signed distance of every point (already in the CAD frame) to the CAD surface.
/// Points beyond `max_distance` [m], or whose closest point is on the border of an open CAD
/// surface with the offset mostly along the surface (the scan runs past the CAD's edge), are
/// unmatched.
/// @param normals_cad empty, or each point's outward normal in the CAD frame: the point is then
/// measured to the closest surface turned less than `facing_deg` from it (and to the closest
/// surface whatever its way when none within `max_distance` is, or its normal is zero). Normals
/// that more than half the points turn away from their closest surface (an inward winding) are
/// not used.
SurfaceDistances measureDeviation(const Model& model,
                                  const Points& points_cad,
                                  double max_distance,
                                  const Points& normals_cad = {},
                                  double facing_deg = 180.0);

/// @brief The paper's verification channel (§3.6.2): per scan point, mean_k |V_k(scan) -
/// V_k(CAD)| between its descriptor cell and the CAD cell it lies on (the nearest CAD cell
/// facing the same way as the CAD surface there). NaN where either is unknown.
/// @param T_cad_scan the registered pose; `scan` holds the scan's descriptors.
/// @param cad_normals from measureDeviation() for the same points.
std::vector<float> shapeDeviation(const DescriptorResult& scan,
                                  const DescriptorResult& cad,
                                  const Eigen::Isometry3d& T_cad_scan,
                                  const Points& cad_normals);

/// @brief Which of the CAD's descriptor cells have a scan point within `distance` [m], raised to
/// 2.5 scan spacings for a scan sparser than that.
std::vector<bool> coveredCells(const Model& model, const Points& points_cad, double distance);

/// @brief Share of the area of the CAD cells with `counted[c]` (every cell when `counted` is
/// empty) that `covered` marks.
double coveredShare(const Model& model,
                    const std::vector<bool>& covered,
                    const std::vector<bool>& counted = {});

/// @brief Share of the CAD surface area (its descriptor cells) that has a scan point within
/// `distance` [m], raised to 2.5 scan spacings for a scan sparser than that.
double surfaceCoverage(const Model& model, const Points& points_cad, double distance);

/// @brief Share of the finite entries of `deviation` inside each one's band, 0 when none is
/// finite: summarizeDeviation()'s in_tolerance_fraction, without its sort.
double inToleranceFraction(const std::vector<float>& deviation, const ToleranceBands& tolerance);

/// @brief Statistics of `deviation` (NaN entries are unmatched) against the tolerance bands;
/// the histogram spans the part's band.
DeviationStatistics summarizeDeviation(const std::vector<float>& deviation,
                                       const ToleranceBands& tolerance,
                                       int histogram_bins);

/// @brief Fills `shape_mean` and `shape_p95` of `stats` from the per-point shape deviation.
void summarizeShapeDeviation(const std::vector<float>& shape, DeviationStatistics* stats);

}  // namespace freeform_inspection
