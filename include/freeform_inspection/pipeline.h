// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/comparison_points.h"
#include "freeform_inspection/correspondence.h"
#include "freeform_inspection/datum_alignment.h"
#include "freeform_inspection/defects.h"
#include "freeform_inspection/descriptor.h"
#include "freeform_inspection/deviation.h"
#include "freeform_inspection/features.h"
#include "freeform_inspection/global_registration.h"
#include "freeform_inspection/icp.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/pose_uncertainty.h"
#include "freeform_inspection/regions.h"
#include "freeform_inspection/scan_cleaning.h"
#include "freeform_inspection/support_plane.h"
#include "freeform_inspection/types.h"

/// @file pipeline.h
/// inspect(): the whole job on one scan, the same call for the CLI and the node. It runs the
/// stages in order (clean → supports → descriptors → features → correspondences → global
/// registration → ICP → deviation → verdict), stops at the first stage that is not ok and reports
/// why.

namespace freeform_inspection {

/// When a registered part is judged.
struct VerdictConfig {
  /// FAIL when fewer evaluated points than this lie inside the tolerance band, even without a
  /// defect region (0 = judge by defect regions only).
  double min_in_tolerance_fraction = 0.0;
  /// NOT_EVALUATED when the scan covers less of the CAD surface than this (0 = any view).
  double min_coverage = 0.0;
  /// [m] Expanded uncertainty U of the measured deviations (scanner, fixture and registration
  /// together, as the quality engineer states it). 0: the tolerance band decides alone (simple
  /// acceptance). Above 0, the decision rule of ISO 14253-1: PASS only where conformance is
  /// proven (inside the band narrowed by U on both sides), FAIL only where nonconformance is
  /// (outside the band widened by U), NOT_EVALUATED between them (ConformanceZones).
  double measurement_uncertainty = 0.0;
};

/// Configuration of the whole pipeline, nested like config/default.yaml.
struct PipelineConfig {
  InputConfig input;
  SupportConfig support;
  DescriptorConfig descriptor;
  FeatureConfig features;
  CorrespondenceConfig correspondence;
  GlobalRegistrationConfig registration;
  IcpConfig icp;
  ToleranceConfig tolerance;
  DeviationConfig deviation;
  DefectConfig defects;
  VerdictConfig verdict;
  /// Named regions with their own band or left out (regions.h); not in config_fields' table:
  /// they come from a regions file (CLI --regions, the node's ~regions_file).
  std::vector<RegionConfig> regions;
  /// Named places read and judged one by one (comparison_points.h); like the regions, from a
  /// file (CLI --points, the node's ~points_file).
  std::vector<ComparisonPointConfig> comparison_points;
  /// The order the datum targets among them fix the pose in (datum_alignment.h); from the same
  /// file's `datum_precedence:`.
  DatumPrecedence datum_precedence;
};

/// @brief Checks every field of the configuration.
/// @return one message per invalid field; empty when the configuration is valid.
std::vector<std::string> validate(const PipelineConfig& config);

/// Outcome of the registration, separate from the part's verdict. kFixed: not registered, the
/// caller's pose taken as it is (inspectAt).
enum class RegistrationStatus { kOk, kAmbiguous, kFailed, kFixed };

const char* toString(RegistrationStatus status);  ///< "ok" | "ambiguous" | "failed" | "fixed"
const char* toString(Verdict verdict);            ///< "PASS" | "FAIL" | "NOT_EVALUATED"

/// Sizes at each stage.
struct InspectionCounts {
  std::size_t scan_points = 0;      ///< finite scan points used
  std::size_t non_finite = 0;       ///< NaN/inf points removed
  std::size_t cropped = 0;          ///< points outside input.crop_box, removed
  std::size_t support_points = 0;   ///< points removed with the supports (support_plane.h)
  std::size_t scan_faces = 0;       ///< triangles of the scan surface (given, or from the grid
                                    ///< of an organized scan); 0 for an unorganized cloud
  std::size_t cad_vertices = 0;     ///< model vertices
  std::size_t features = 0;         ///< rare features selected on the scan
  std::size_t candidates = 0;       ///< CAD candidates for those features
  std::size_t correspondences = 0;  ///< correspondences kept after the triangle check
};

/// The zones of the ISO 14253-1 decision rule and what the deviation map shows in each; filled
/// when verdict.measurement_uncertainty U is above 0 and the deviation was measured.
struct ConformanceZones {
  double measurement_uncertainty = 0.0;  ///< [m] U; 0 = not applied
  /// [m] Conformance is proven inside [acceptance_lower, acceptance_upper] (the band narrowed by
  /// U), empty (lower > upper) when U is half the band or more.
  double acceptance_lower = 0.0;
  double acceptance_upper = 0.0;
  /// [m] Nonconformance is proven outside [rejection_lower, rejection_upper] (the band widened).
  double rejection_lower = 0.0;
  double rejection_upper = 0.0;
  /// Defect regions (defects.h, the same rules) outside the acceptance zone, and outside the
  /// rejection limits.
  std::size_t regions_outside_acceptance = 0;
  std::size_t regions_beyond_rejection = 0;
  /// Share of the evaluated points inside the acceptance zone, and inside the rejection limits.
  double inside_acceptance_fraction = 0.0;
  double inside_rejection_fraction = 0.0;
};

/// How one named region (PipelineConfig::regions) came out.
struct RegionResult {
  std::string name;
  bool evaluated = true;      ///< false: left out of the verdict (RegionConfig::evaluate)
  ToleranceConfig tolerance;  ///< the band it was judged against
  /// Its scan points' statistics (those whose closest CAD point lies in it); coverage is the
  /// share of its CAD surface with scan points near it.
  DeviationStatistics deviation;
  std::size_t defects = 0;  ///< defect regions in it
  /// With a measurement uncertainty U (ConformanceZones): defect regions in it beyond its band
  /// widened by U, and outside its band narrowed by U.
  std::size_t defects_beyond_rejection = 0;
  std::size_t defects_outside_acceptance = 0;
  Verdict verdict = Verdict::kNotEvaluated;
  std::string verdict_reason;
};

/// Wall time of one stage.
struct StageTiming {
  std::string stage;     ///< stage name
  double seconds = 0.0;  ///< [s]
};

/// Everything one inspection produced.
struct InspectionResult {
  Status status;  ///< first stage that failed, or ok
  RegistrationStatus registration = RegistrationStatus::kFailed;
  Verdict verdict = Verdict::kNotEvaluated;
  std::string verdict_reason;  ///< why PASS, FAIL or NOT_EVALUATED, naming the quantities
  Eigen::Isometry3d T_cad_scan = Eigen::Isometry3d::Identity();  ///< scan → CAD
  std::vector<Eigen::Isometry3d> alternatives;                   ///< other poses when ambiguous
  double rmse = std::numeric_limits<double>::quiet_NaN();        ///< [m] inlier RMS distance
  double fitness = 0.0;  ///< share of scan points within the inlier distance
  double inlier_distance = std::numeric_limits<double>::quiet_NaN();  ///< [m] 3σ, bounded
  double noise_sigma = std::numeric_limits<double>::quiet_NaN();  ///< [m] robust σ of residuals
  double score = 0.0;  ///< verification score of the pose: share of the scan it explains
  /// Score of the best distinct rival pose over the pose's own (0..1, at a truncation of 3σ of
  /// the fit): near 1 for a view a symmetric part looks the same in; 0 when no distinct pose
  /// came within 80 % of it in the quick ranking, or before a pose was chosen.
  double ambiguity = 0.0;
  double scan_noise = std::numeric_limits<double>::quiet_NaN();  ///< [m] the scan's own noise
  /// Share of the scan's surface (linked cells) within the inlier distance of the CAD at the
  /// pose: 1 for a right pose on a clean scan, whatever its outliers (surface_support.h).
  double surface_on_cad = std::numeric_limits<double>::quiet_NaN();
  /// How much of the curve the CAD's faces stand for (chord_error.h) the pose is fitted to: 0
  /// the faces as they are; 0.5-1 when a low-noise scan shows that it follows the curve a
  /// coarsely exported CAD cuts (registration.md, "A coarse CAD"). Deviations stay measured
  /// from the faces.
  double cad_curve_share = 0.0;
  /// inspectFrom(): how far the registered pose lies from the given one, the turn [deg] and the
  /// shift of the scan's centroid [m]: where the given pose is a fixture's nominal pose, how far
  /// the part sat from it. inspectAt(): how far the pose inspectFrom() would register lies from
  /// the given one, which the deviation is measured at. NaN for inspect() and when no pose was
  /// registered.
  double offset_from_initial_deg = std::numeric_limits<double>::quiet_NaN();
  double offset_from_initial = std::numeric_limits<double>::quiet_NaN();  ///< [m]
  /// How far the scan's noise leaves the pose free (pose_uncertainty.h); known once the
  /// deviation is measured (registration ok or ambiguous).
  PoseUncertainty pose_uncertainty;
  DeviationStatistics deviation;      ///< empty unless the registration is ok or ambiguous
  std::vector<DefectRegion> defects;  ///< largest |peak| first
  std::vector<RegionResult> regions;  ///< one per named region, in the configuration's order
  ConformanceZones conformance;  ///< the guard bands' decision (verdict.measurement_uncertainty)
  /// One per configured comparison point, in the configuration's order (comparison_points.h).
  std::vector<ComparisonPointResult> comparison_points;
  /// The frame the comparison points' datum targets fix (datum_alignment.h), when some point
  /// names a datum: `T_cad_scan` is then its pose, and the registration's best fit is kept here.
  DatumAlignment datum_alignment;
  DeviationMap deviation_map;  ///< per scan point, CAD frame (empty when failed)
  Triangles scan_faces;        ///< the cleaned scan's triangles (indices into the map)
  InspectionCounts counts;
  std::vector<StageTiming> timings;   ///< per stage, last entry "total"
  std::vector<std::string> warnings;  ///< non-fatal findings for the caller to log

  /// The name of named region `region` (DefectRegion::region, DeviationMap::region); "" for -1,
  /// the rest of the part (a region's name is never empty).
  std::string regionName(int region) const;
};

/// Called with the name of the stage about to start ("clean", "descriptors", "features",
/// "correspondences", "global_registration", "icp", "deviation") and the rough share of the
/// work done so far (0..1). Returning false stops the inspection before that stage: status
/// kCancelled, verdict NOT_EVALUATED. Called on the caller's thread.
using ProgressCallback = std::function<bool(const std::string& stage, double fraction)>;

/// @brief Inspects one scan against a model.
/// @param scan points in metres in the scanner's frame; non-finite points are removed and
/// counted.
/// @throw std::invalid_argument if `config` does not validate (a caller error).
/// @param progress optional: stage reports and cancellation between stages.
InspectionResult inspect(const Model& model,
                         const Scan& scan,
                         const PipelineConfig& config,
                         const ProgressCallback& progress = {});

/// @brief inspect() for a scan whose pose is known roughly (the fixture's nominal pose, a pose
/// the robot's kinematics give): no features, correspondences or global search; ICP starts
/// from `initial_T_cad_scan` (scan → CAD) and the pose must pass the same checks that it
/// explains the scan. ICP's first cut-off is registration.verification_distance_cells cells,
/// so the guess must put the scan within about that of the CAD surface. No rival poses are
/// sought: a symmetric part's twin is not reported `ambiguous` here.
/// @return as inspect(); status kInvalidInput when the initial pose is not a finite rigid
/// transform.
InspectionResult inspectFrom(const Model& model,
                             const Scan& scan,
                             const Eigen::Isometry3d& initial_T_cad_scan,
                             const PipelineConfig& config,
                             const ProgressCallback& progress = {});

/// @brief The inspection at a given pose, not registered (a fixture that locates the part: the
/// deviation in the fixture's frame, where the part sitting off its seat is a deviation too).
/// Registration status kFixed; T_cad_scan is `T_cad_scan` as given; the fit's numbers (RMS,
/// fitness, surface on the CAD) are measured there and gate nothing. The verdict is judged as
/// after a registration: NOT_EVALUATED when the scan does not cover the CAD there. How far the
/// part sits from the pose is measured by inspectFrom()'s refinement and reported in
/// offset_from_initial (NaN, with a warning, when no pose near it explains the scan); the pose
/// covariance is not known (no fit).
/// @return as inspect(); status kInvalidInput when the pose is not a finite rigid transform.
InspectionResult inspectAt(const Model& model,
                           const Scan& scan,
                           const Eigen::Isometry3d& T_cad_scan,
                           const PipelineConfig& config,
                           const ProgressCallback& progress = {});

}  // namespace freeform_inspection
