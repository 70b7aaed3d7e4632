// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/comparison_points.h"
#include "freeform_inspection/types.h"

/// @file datum_alignment.h
/// Datum alignment (docs/inspection.md, "Datum alignment"): the part measured in the frame its
/// drawing's datum targets fix, not in the best fit's. A turbine blade's six-point nest, a
/// stamping's RPS points, a casting's 3-2-1 scheme: the datum targets are comparison points
/// marked with the datum they belong to, and the pose is moved until the scan's surface passes
/// through every one of them. The best fit spreads a part's form error over the whole surface;
/// the datum alignment puts it where the drawing measures it from.
///
/// A target on a surface fixes one degree of freedom: the scan's deviation there along the CAD
/// normal. Six targets whose normals hold all six motions fix the pose (3-2-1: three on the
/// primary datum's surface, two on the secondary's, one on the tertiary's). More are fitted in
/// the datums' order of precedence (DatumPrecedence): the primary's targets by least squares
/// over every motion they hold, the secondary's over the motions the primary left free, and so
/// on; or all at once, weighted alike. Each round reads every target as a comparison point
/// (readAround()), solves the linearized motion that brings the readings to zero, and moves the
/// pose by it.

namespace freeform_inspection {

class MeshQuery;

/// One datum target's readings.
struct DatumTargetReading {
  std::string name;
  std::string datum;
  Eigen::Vector3d nominal = Eigen::Vector3d::Zero();  ///< [m] on the CAD surface
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();   ///< outward CAD normal
  /// [m] The scan's deviation there at the pose the alignment started from (the best fit), and
  /// at the datum alignment (its residual: 0 within the readings' noise for exactly six).
  double best_fit = std::numeric_limits<double>::quiet_NaN();
  double aligned = std::numeric_limits<double>::quiet_NaN();
  std::size_t points = 0;  ///< scan points read at the last reading
};

/// How the datum alignment went.
struct DatumAlignment {
  bool requested = false;  ///< some comparison point names a datum
  bool aligned = false;    ///< the pose is the datum alignment's
  std::string message;     ///< how it went, or why it could not align (the pose then stays)
  /// The pose it started from (the registration's best fit) and how far it moved from it: the
  /// turn [deg] and the shift of the scan's centroid [m].
  Eigen::Isometry3d T_cad_scan_best_fit = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_cad_scan = Eigen::Isometry3d::Identity();  ///< aligned (when `aligned`)
  double turn_deg = std::numeric_limits<double>::quiet_NaN();
  double shift = std::numeric_limits<double>::quiet_NaN();
  int rounds = 0;
  /// Smallest over largest singular value of the targets' constraints (rotations scaled by the
  /// targets' spread): 0 when a motion is free, 1 for a perfectly balanced scheme.
  double conditioning = std::numeric_limits<double>::quiet_NaN();
  /// How far the readings' noise leaves the frame free (each a median of its points, carried
  /// through the solve): 1σ turn about the least held axis [deg], and 1σ shift of the targets'
  /// centre along the least held direction [m]. NaN until aligned.
  double rotation_std_deg = std::numeric_limits<double>::quiet_NaN();
  double translation_std = std::numeric_limits<double>::quiet_NaN();
  std::vector<DatumTargetReading> targets;  ///< in the configuration's order
  /// The datums in the order they fixed the pose, primary first; empty when every target was
  /// weighted alike (DatumPrecedence::alike).
  std::vector<std::string> precedence;
};

/// Targets fewer than this cannot fix a rigid pose.
constexpr std::size_t kMinDatumTargets = 6;
/// Targets whose constraints hold the weakest motion less than this share of the strongest are
/// refused: a reading's error would move the pose along that motion 50 times over.
constexpr double kMinDatumConditioning = 0.02;
/// Rounds at most; each reads every target again where the last one moved the pose.
constexpr int kMaxDatumRounds = 20;

/// @brief Whether some of `points` names a datum (is a datum target).
bool hasDatumTargets(const std::vector<ComparisonPointConfig>& points);

/// @brief The datums of `points` in the order they fix the pose: `precedence.order` when given,
/// else their labels in alphabetical order; empty when `precedence.alike`.
std::vector<std::string> datumOrder(const DatumPrecedence& precedence,
                                    const std::vector<ComparisonPointConfig>& points);

/// @brief The order as reports and the configuration hash give it: "A, B, C", or "none (every
/// target alike)".
std::string datumPrecedenceText(const DatumPrecedence& precedence,
                                const std::vector<ComparisonPointConfig>& points);

/// @brief The pose at which the scan's surface passes through every datum target, starting
/// from `T_cad_scan` (the best fit). Comparison points without a datum are ignored; without
/// any, nothing is done (`requested` false). When the targets are fewer than six, leave a
/// motion free, lie off the CAD or are not all read, `aligned` is false and `message` says
/// which; the caller keeps its pose. Where the targets hold a motion more than once, the datum
/// first in `precedence` fixes it (validate(const DatumPrecedence&, ...) must pass).
/// @param scan_points the scan in its own frame [m]
/// @param default_radius [m] the radius of targets without one (the model's cell)
/// @param max_distance [m] scan points farther from the CAD are not read (the deviation map's
/// cut-off)
DatumAlignment alignToDatums(const MeshQuery& cad,
                             const Points& scan_points,
                             const Eigen::Isometry3d& T_cad_scan,
                             const std::vector<ComparisonPointConfig>& points,
                             const DatumPrecedence& precedence,
                             double default_radius,
                             double max_distance);

}  // namespace freeform_inspection
