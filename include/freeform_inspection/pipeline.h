// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/correspondence.h"
#include "freeform_inspection/descriptor.h"
#include "freeform_inspection/features.h"
#include "freeform_inspection/global_registration.h"
#include "freeform_inspection/icp.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/scan_cleaning.h"
#include "freeform_inspection/types.h"

/// @file pipeline.h
/// inspect(): the whole job on one scan, the same call for the CLI and the node. It runs the
/// stages in order (clean → descriptors → features → correspondences → global registration →
/// ICP → deviation → verdict), stops at the first stage that is not ok and reports why.

namespace freeform_inspection {

/// Tolerance band on the signed deviation.
struct ToleranceConfig {
  double upper = 1e-4;   ///< [m] largest allowed positive deviation (excess material)
  double lower = -1e-4;  ///< [m] most negative allowed deviation (missing material)
};

/// Configuration of the whole pipeline, nested like config/default.yaml.
struct PipelineConfig {
  InputConfig input;
  DescriptorConfig descriptor;
  FeatureConfig features;
  CorrespondenceConfig correspondence;
  GlobalRegistrationConfig registration;
  IcpConfig icp;
  ToleranceConfig tolerance;
};

/// @brief Checks every field of the configuration.
/// @return one message per invalid field; empty when the configuration is valid.
std::vector<std::string> validate(const PipelineConfig& config);

/// Outcome of the registration, separate from the part's verdict.
enum class RegistrationStatus { kOk, kAmbiguous, kFailed };

/// The part's verdict. PASS/FAIL only after a registration that passed its quality gates.
enum class Verdict { kPass, kFail, kNotEvaluated };

const char* toString(RegistrationStatus status);  ///< "ok" | "ambiguous" | "failed"
const char* toString(Verdict verdict);            ///< "PASS" | "FAIL" | "NOT_EVALUATED"

/// Statistics of the signed deviation over the evaluated scan points. Lengths in metres.
struct DeviationStatistics {
  std::size_t evaluated = 0;           ///< points with a CAD surface within reach
  std::size_t unmatched = 0;           ///< points too far from the CAD to be part of it
  double mean = 0.0;                   ///< [m]
  double std = 0.0;                    ///< [m]
  double rms = 0.0;                    ///< [m]
  double min = 0.0;                    ///< [m]
  double max = 0.0;                    ///< [m]
  double p5 = 0.0;                     ///< [m]
  double p50 = 0.0;                    ///< [m]
  double p95 = 0.0;                    ///< [m]
  double in_tolerance_fraction = 0.0;  ///< share of evaluated points inside the band
  double coverage = 0.0;               ///< share of CAD area with scan points near it
};

/// A connected out-of-tolerance region.
struct DefectRegion {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< [m] CAD frame
  std::size_t points = 0;                              ///< scan points in the region
  double area = 0.0;                                   ///< [m^2]
  double peak = 0.0;                                   ///< [m] signed, largest magnitude
};

/// Sizes at each stage.
struct InspectionCounts {
  std::size_t scan_points = 0;      ///< finite scan points used
  std::size_t non_finite = 0;       ///< NaN/inf points removed
  std::size_t scan_faces = 0;       ///< triangles of the scan surface (given, or from the grid
                                    ///< of an organized scan); 0 for an unorganized cloud
  std::size_t cad_vertices = 0;     ///< model vertices
  std::size_t features = 0;         ///< rare features selected on the scan
  std::size_t candidates = 0;       ///< CAD candidates for those features
  std::size_t correspondences = 0;  ///< correspondences kept after the triangle check
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
  Eigen::Isometry3d T_cad_scan = Eigen::Isometry3d::Identity();  ///< scan → CAD
  std::vector<Eigen::Isometry3d> alternatives;                   ///< other poses when ambiguous
  double rmse = std::numeric_limits<double>::quiet_NaN();        ///< [m] inlier RMS distance
  double fitness = 0.0;  ///< share of scan points within the inlier distance
  double inlier_distance = std::numeric_limits<double>::quiet_NaN();  ///< [m] 3σ, bounded
  double noise_sigma = std::numeric_limits<double>::quiet_NaN();  ///< [m] robust σ of residuals
  double score = 0.0;  ///< verification score of the pose: share of the scan it explains
  double scan_noise = std::numeric_limits<double>::quiet_NaN();  ///< [m] the scan's own noise
  DeviationStatistics deviation;
  std::vector<DefectRegion> defects;
  InspectionCounts counts;
  std::vector<StageTiming> timings;   ///< per stage, last entry "total"
  std::vector<std::string> warnings;  ///< non-fatal findings for the caller to log
};

/// @brief Inspects one scan against a model.
/// @param scan points in metres in the scanner's frame; non-finite points are removed and
/// counted.
/// @throw std::invalid_argument if `config` does not validate (a caller error).
InspectionResult inspect(const Model& model, const Scan& scan, const PipelineConfig& config);

}  // namespace freeform_inspection
