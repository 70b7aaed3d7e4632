// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "freeform_inspection/deviation.h"
#include "freeform_inspection/regions.h"
#include "freeform_inspection/types.h"

/// @file comparison_points.h
/// Comparison points (docs/inspection.md, "Comparison points"): named places on the CAD surface
/// where the drawing asks for the deviation itself (a leading-edge station, a datum pad), each
/// read from the scan points around it and judged against a band of its own or of the surface
/// there. A comparison point the scan does not show leaves the part NOT_EVALUATED, one outside
/// its band fails it.

namespace freeform_inspection {

class MeshQuery;

/// One named place and how it is judged.
struct ComparisonPointConfig {
  std::string name;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< [m] CAD frame, on (or by) the surface
  /// Its own band; when false, the band of the surface there (its region's, or the part's).
  bool has_tolerance = false;
  ToleranceConfig tolerance;
  /// [m] Scan points whose foot on the CAD lies within this distance of the place are read;
  /// 0: the model's surface-graph cell (0.6 r_1, about 1 % of the CAD's diagonal).
  double radius = 0.0;
  /// The datum this point is a target of ("A", "B", ...; datum_alignment.h), empty for none.
  /// With six or more targets the deviation is measured in the frame the datum targets fix
  /// (3-2-1, RPS) instead of the best fit's.
  std::string datum;
};

/// The order in which the datums of the targets fix the pose (datum_alignment.h): the drawing's
/// datum reference frame, |A|B|C|. The primary datum's targets are fitted first, as far as they
/// hold the pose; the secondary's then fix what the primary left free, and so on. By default the
/// labels in alphabetical order; `alike` fits every target at once by least squares, weighted
/// alike (an RPS scheme whose over-held axes are best-fitted).
struct DatumPrecedence {
  bool alike = false;
  /// The datums, primary first; empty (and not `alike`): the targets' labels in alphabetical
  /// order. When given, it must name every target's datum, and only those.
  std::vector<std::string> order;
};

/// What the scan shows at one comparison point.
struct ComparisonPointResult {
  std::string name;
  std::string datum;  ///< ComparisonPointConfig::datum
  /// [m] The configured place moved onto the CAD surface (its closest point there), and the
  /// outward normal the deviation is measured along.
  Eigen::Vector3d nominal = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double off_surface = 0.0;   ///< [m] how far the configured place lies from the CAD surface
  double radius = 0.0;        ///< [m] the radius read
  ToleranceConfig tolerance;  ///< the band it is judged against
  /// Scan points read, their median signed deviation (NaN when fewer than
  /// kMinComparisonPoints) and the spread of their deviations (standard deviation).
  std::size_t points = 0;
  double deviation = std::numeric_limits<double>::quiet_NaN();  ///< [m]
  double spread = std::numeric_limits<double>::quiet_NaN();     ///< [m]
  Verdict verdict = Verdict::kNotEvaluated;
  std::string verdict_reason;
  bool measured() const { return points > 0 && deviation == deviation; }
};

/// Fewer scan points than this around a comparison point: not measured.
constexpr std::size_t kMinComparisonPoints = 3;
/// A configured place farther than this many radii from the CAD surface is refused (not
/// measured): a place in millimetres or in another frame.
constexpr double kMaxOffSurfaceRadii = 5.0;

/// Where a comparison point lies on the CAD (placeComparisonPoint()).
struct PlacedPoint {
  bool found = false;                                 ///< false: no CAD surface to place it on
  Eigen::Vector3d nominal = Eigen::Vector3d::Zero();  ///< [m] closest point on the CAD surface
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();   ///< outward CAD normal there
  double off_surface = 0.0;                           ///< [m] from the configured position
  double radius = 0.0;                                ///< [m] the radius read
  /// false when the position lies more than kMaxOffSurfaceRadii radii off the surface
  bool near_surface() const { return found && off_surface <= kMaxOffSurfaceRadii * radius; }
};

/// @brief The configured position moved onto the CAD surface, and the radius read there (the
/// point's own, else `default_radius`).
PlacedPoint placeComparisonPoint(const ComparisonPointConfig& point,
                                 const MeshQuery& cad,
                                 double default_radius);

/// What the scan shows around one place.
struct PlaceReading {
  std::size_t points = 0;                                       ///< scan points read
  double deviation = std::numeric_limits<double>::quiet_NaN();  ///< [m] their median
  double spread = std::numeric_limits<double>::quiet_NaN();     ///< [m] standard deviation
  bool measured() const { return points >= kMinComparisonPoints; }
};

/// @brief The scan points (CAD frame, with their signed `deviation`, NaN unmatched) whose foot
/// lies within the place's radius: a point's foot is the point moved back along the place's
/// normal by its own deviation, so a point of a wall's far side, or of a surface beyond an edge,
/// is not read. Median and spread only when kMinComparisonPoints or more are read.
PlaceReading readAround(const PlacedPoint& place,
                        const Points& points_cad,
                        const std::vector<float>& deviation);

/// @brief One message per invalid field of each point (named by its name or position); empty
/// when valid. Names must be unique and non-empty, positions finite, radii finite and ≥ 0.
std::vector<std::string> validate(const std::vector<ComparisonPointConfig>& points);

/// @brief One message per fault of a precedence against the targets `points` name: a datum
/// listed twice or without targets, a target's datum not listed; empty when valid.
std::vector<std::string> validate(const DatumPrecedence& precedence,
                                  const std::vector<ComparisonPointConfig>& points);

/// Result of reading a comparison points file.
struct ComparisonPointsLoadResult {
  Status status;  ///< kInvalidInput naming every bad or unknown key
  std::vector<ComparisonPointConfig> points;
  DatumPrecedence datum_precedence;
};

/// @brief Reads comparison points from YAML: a top-level `points:` list of maps with `name`,
/// `position: [x, y, z]` (metres in the CAD frame), optional `tolerance: {upper, lower}`,
/// `radius` (metres) and `datum`; beside the list, an optional `datum_precedence:` list of
/// datums, primary first, or `none` (DatumPrecedence::alike). Unknown keys are errors, as in
/// the configuration file.
ComparisonPointsLoadResult parseComparisonPoints(const std::string& yaml_text);

/// @brief parseComparisonPoints() of a file; an unreadable file is kInvalidInput naming it.
ComparisonPointsLoadResult loadComparisonPointsFile(const std::string& path);

/// @brief Reads each comparison point from the deviation map: the median signed deviation of
/// the scan points (`map`, CAD frame) whose foot on the CAD surface lies within the radius of
/// the place's closest point on it. The foot of a point is taken as the point moved back along
/// the place's normal by its own deviation, so a point of a wall's far side, or of a surface
/// beyond an edge, is not read. A point without a band of its own takes the band of the surface
/// at its nominal place: its region's (`regions`), else `part_tolerance`. Verdicts are left to
/// judgeComparisonPoint().
std::vector<ComparisonPointResult> readComparisonPoints(
    const std::vector<ComparisonPointConfig>& points,
    const std::vector<RegionConfig>& regions,
    const ToleranceConfig& part_tolerance,
    const MeshQuery& cad,
    const DeviationMap& map,
    double default_radius);

/// @brief The verdict of one measured point: PASS inside its band, FAIL outside it; with a
/// measurement uncertainty U > 0 (ISO 14253-1), PASS only inside the band narrowed by U, FAIL
/// only outside the band widened by U, NOT_EVALUATED between them. Not measured: NOT_EVALUATED.
void judgeComparisonPoint(double measurement_uncertainty, ComparisonPointResult* point);

}  // namespace freeform_inspection
