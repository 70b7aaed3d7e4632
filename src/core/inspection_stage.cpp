// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// After the registration: deviation, defects and the verdict (docs/inspection.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "pipeline_internal.h"

#include "freeform_inspection/defects.h"
#include "freeform_inspection/deviation.h"

namespace freeform_inspection::internal {
namespace {

std::string describeDefect(const DefectRegion& defect) {
  char text[160];
  std::snprintf(text,
                sizeof(text),
                "%s of %.3g mm peak over %.3g mm^2 at (%.4g, %.4g, %.4g) m",
                defect.sign < 0 ? "dent (missing material)" : "bump (excess material)",
                defect.peak * 1e3,
                defect.area * 1e6,
                defect.centroid.x(),
                defect.centroid.y(),
                defect.centroid.z());
  return text;
}

}  // namespace

std::string formatLength(double metres) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g mm", metres * 1e3);
  return text;
}

// Deviation, statistics, shape deviation and defect regions of a registered scan.
void measurePart(const Model& model,
                 const Scan& scan,
                 const DescriptorResult& descriptors,
                 const PipelineConfig& config,
                 InspectionResult* result) {
  DeviationMap& map = result->deviation_map;
  map.points.resize(scan.points.size());
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    map.points[i] = result->T_cad_scan * scan.points[i];
  }
  const double diagonal = model.bounds().diagonal();
  SurfaceDistances distances =
      measureDeviation(model, map.points, config.deviation.max_distance_ratio * diagonal);
  map.deviation = std::move(distances.deviation);
  result->pose_uncertainty = estimatePoseUncertainty(map.points,
                                                     distances.normals,
                                                     map.deviation,
                                                     result->T_cad_scan,
                                                     result->inlier_distance,
                                                     result->noise_sigma,
                                                     diagonal);
  map.shape_deviation =
      shapeDeviation(descriptors, model.descriptors(), result->T_cad_scan, distances.normals);
  result->deviation =
      summarizeDeviation(map.deviation, config.tolerance, config.deviation.histogram_bins);
  summarizeShapeDeviation(map.shape_deviation, &result->deviation);
  result->deviation.coverage = surfaceCoverage(
      model, map.points, config.deviation.coverage_distance_cells * model.cellSize());
  DefectResult defects =
      findDefects(map.points, scan.faces, map.deviation, config.tolerance, config.defects);
  result->defects = std::move(defects.regions);
  map.defect = std::move(defects.point_region);
  result->scan_faces = scan.faces;
  // A band narrower than the residual noise of the fit flags scattered points, not the part.
  const double band = std::min(config.tolerance.upper, -config.tolerance.lower);
  if (std::isfinite(result->noise_sigma) && band < 3.0 * result->noise_sigma) {
    result->warnings.push_back("the tolerance band (" + formatLength(config.tolerance.lower) +
                               " to " + formatLength(config.tolerance.upper) +
                               ") is narrower than 3x the fit's residual noise (sigma " +
                               formatLength(result->noise_sigma) +
                               "): scattered points fall outside it by noise alone");
  }
}

// The part's verdict, kept apart from how sure the registration is.
void judge(const PipelineConfig& config, InspectionResult* result) {
  const DeviationStatistics& stats = result->deviation;
  const std::string band = "[" + formatLength(config.tolerance.lower) + ", " +
                           formatLength(config.tolerance.upper) + "]";
  result->verdict = Verdict::kNotEvaluated;
  if (result->status.code == StatusCode::kCancelled) {
    result->verdict_reason = "not evaluated: " + result->status.message;
    return;
  }
  if (result->registration == RegistrationStatus::kFailed) {
    result->verdict_reason = "not evaluated: " + result->status.message;
    return;
  }
  if (result->registration == RegistrationStatus::kAmbiguous) {
    result->verdict_reason = "not evaluated: the pose is ambiguous (" + result->status.message +
                             "); the deviation shown is for the best pose";
    return;
  }
  if (stats.evaluated == 0) {
    result->verdict_reason = "not evaluated: no scan point lies on the CAD surface";
    return;
  }
  if (stats.coverage < config.verdict.min_coverage) {
    result->verdict_reason = "not evaluated: the scan covers " + std::to_string(stats.coverage) +
                             " of the CAD surface (" + "verdict.min_coverage " +
                             std::to_string(config.verdict.min_coverage) + ")";
    return;
  }
  if (!result->defects.empty()) {
    result->verdict = Verdict::kFail;
    result->verdict_reason = std::to_string(result->defects.size()) +
                             " region(s) outside the tolerance band " + band +
                             "; largest: " + describeDefect(result->defects.front());
    return;
  }
  if (stats.in_tolerance_fraction < config.verdict.min_in_tolerance_fraction) {
    result->verdict = Verdict::kFail;
    result->verdict_reason = "only " + std::to_string(stats.in_tolerance_fraction) +
                             " of the points lie inside the tolerance band " + band +
                             " (verdict.min_in_tolerance_fraction " +
                             std::to_string(config.verdict.min_in_tolerance_fraction) + ")";
    return;
  }
  result->verdict = Verdict::kPass;
  result->verdict_reason = "no region of " + std::to_string(config.defects.min_points) +
                           " or more connected points outside the tolerance band " + band + "; " +
                           std::to_string(stats.in_tolerance_fraction) + " of " +
                           std::to_string(stats.evaluated) + " points inside it, deviation " +
                           formatLength(stats.min) + " to " + formatLength(stats.max);
}

}  // namespace freeform_inspection::internal
