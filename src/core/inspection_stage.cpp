// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// After the registration: deviation, defects and the verdict (docs/inspection.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "pipeline_internal.h"

#include "freeform_inspection/chord_error.h"
#include "freeform_inspection/defects.h"
#include "freeform_inspection/deviation.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/regions.h"

namespace freeform_inspection::internal {
namespace {

std::string describeDefect(const DefectRegion& defect, const InspectionResult& result) {
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
  const std::string region = result.regionName(defect.region);
  return region.empty() ? std::string(text) : text + (" in region '" + region + "'");
}

// The size a region needs to count, as a PASS's reason states it.
std::string regionSize(const DefectConfig& defects) {
  std::string size = std::to_string(defects.min_points) + " or more connected points";
  if (defects.min_area > 0.0) {
    char area[48];
    std::snprintf(area, sizeof(area), " over %.3g mm^2 or more", defects.min_area * 1e6);
    size += area;
  }
  return size;
}

// Each point's band widened (by u > 0) or narrowed (u < 0). A band that narrowing empties holds
// no deviation but 0 exactly: every point there lies outside it, so nothing there can be proven
// to conform (ISO 14253-1), while it still judges the other points.
ToleranceBands shiftedBands(const ToleranceBands& bands, double u) {
  const auto shift = [u](const ToleranceConfig& band) {
    const ToleranceConfig moved{band.upper + u, band.lower - u};
    return moved.lower < moved.upper ? moved : ToleranceConfig{0.0, 0.0};
  };
  ToleranceBands shifted(shift(bands.part));
  for (const ToleranceConfig& band : bands.region_bands) {
    shifted.region_bands.push_back(shift(band));
  }
  shifted.region_of = bands.region_of;
  return shifted;
}

// The regions and shares of the deviation map in the zones of ISO 14253-1's decision rule:
// the bands narrowed by U (acceptance) and widened by U (rejection beyond it). The same region
// rules as the defects, so a zone's verdict and the defect list agree where U is 0. The zones'
// limits reported are the part's band's.
ConformanceZones conformanceZones(const std::vector<float>& deviation,
                                  DefectNeighbourhood& surface,
                                  const ToleranceBands& bands,
                                  const PipelineConfig& config,
                                  std::vector<RegionResult>* regions) {
  ConformanceZones zones;
  const double u = config.verdict.measurement_uncertainty;
  if (!(u > 0.0)) {
    return zones;
  }
  zones.measurement_uncertainty = u;
  const ToleranceBands rejection = shiftedBands(bands, u);
  zones.rejection_lower = rejection.part.lower;
  zones.rejection_upper = rejection.part.upper;
  const DefectResult beyond = findDefects(surface, deviation, rejection, config.defects);
  zones.regions_beyond_rejection = beyond.regions.size();
  zones.inside_rejection_fraction = inToleranceFraction(deviation, rejection);
  zones.acceptance_lower = config.tolerance.lower + u;
  zones.acceptance_upper = config.tolerance.upper - u;
  // No band with an acceptance zone proves nothing conforms; judge() says so.
  const auto opens = [u](const ToleranceConfig& band) { return band.lower + u < band.upper - u; };
  DefectResult outside;
  if (opens(bands.part) ||
      std::any_of(bands.region_bands.begin(), bands.region_bands.end(), opens)) {
    const ToleranceBands acceptance = shiftedBands(bands, -u);
    outside = findDefects(surface, deviation, acceptance, config.defects);
    zones.regions_outside_acceptance = outside.regions.size();
    zones.inside_acceptance_fraction = inToleranceFraction(deviation, acceptance);
  }
  // Each named region's share of them, for its own verdict.
  const auto countIn = [regions](const DefectResult& found, std::size_t RegionResult::*count) {
    for (const DefectRegion& defect : found.regions) {
      if (defect.region >= 0) {
        ++((*regions)[static_cast<std::size_t>(defect.region)].*count);
      }
    }
  };
  countIn(beyond, &RegionResult::defects_beyond_rejection);
  countIn(outside, &RegionResult::defects_outside_acceptance);
  return zones;
}

// judge() with the guard bands of ISO 14253-1 (verdict.measurement_uncertainty > 0).
void judgeWithUncertainty(const PipelineConfig& config, InspectionResult* result) {
  const ConformanceZones& zones = result->conformance;
  const double min_inside = config.verdict.min_in_tolerance_fraction;
  const std::string u =
      "the measurement uncertainty U " + formatLength(zones.measurement_uncertainty);
  const std::string rejection =
      "[" + formatLength(zones.rejection_lower) + ", " + formatLength(zones.rejection_upper) + "]";
  const std::string acceptance = "[" + formatLength(zones.acceptance_lower) + ", " +
                                 formatLength(zones.acceptance_upper) + "]";
  if (zones.regions_beyond_rejection > 0) {
    result->verdict = Verdict::kFail;
    result->verdict_reason =
        std::to_string(zones.regions_beyond_rejection) +
        " region(s) outside the tolerance band widened by " + u + " " + rejection +
        " (nonconformance proven, ISO 14253-1); largest: " +
        (result->defects.empty() ? std::string("-")
                                 : describeDefect(result->defects.front(), *result));
    return;
  }
  if (zones.inside_rejection_fraction < min_inside) {
    result->verdict = Verdict::kFail;
    result->verdict_reason = "only " + std::to_string(zones.inside_rejection_fraction) +
                             " of the points lie inside the tolerance band widened by " + u + " " +
                             rejection + " (verdict.min_in_tolerance_fraction " +
                             std::to_string(min_inside) + "; nonconformance proven)";
    return;
  }
  if (!(zones.acceptance_lower < zones.acceptance_upper)) {
    result->verdict_reason = "not evaluated: " + u +
                             " is half the tolerance band or more, so no part can be proven to "
                             "conform (ISO 14253-1); none lies beyond " +
                             rejection;
    return;
  }
  if (zones.regions_outside_acceptance == 0 && zones.inside_acceptance_fraction >= min_inside) {
    result->verdict = Verdict::kPass;
    result->verdict_reason =
        "no region of " + regionSize(config.defects) + " outside the acceptance zone " +
        acceptance + " (the tolerance band narrowed by " + u +
        ": conformance proven, ISO 14253-1); " + std::to_string(zones.inside_acceptance_fraction) +
        " of " + std::to_string(result->deviation.evaluated) + " points inside it";
    return;
  }
  result->verdict_reason =
      "not evaluated: neither conformance nor nonconformance is proven (ISO 14253-1): " +
      std::to_string(zones.regions_outside_acceptance) +
      " region(s) lie outside the acceptance zone " + acceptance + ", none outside " + rejection +
      " (the tolerance band narrowed and widened by " + u + ")";
  if (min_inside > 0.0) {
    result->verdict_reason += "; " + std::to_string(zones.inside_acceptance_fraction) +
                              " of the points inside the acceptance zone (" +
                              "verdict.min_in_tolerance_fraction " + std::to_string(min_inside) +
                              ")";
  }
}

}  // namespace

std::string formatLength(double metres) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g mm", metres * 1e3);
  return text;
}

namespace {

// A CAD exported coarsely shows its facets in the deviation map of a good part (chord_error.h).
// Each defect region gets the chord error of the faces it lies on (`faces`: each point's, from
// measureDeviation()); the result warns where that error is more than a tenth of the tolerance
// band (the 10:1 rule for a measuring instrument's resolution) and names the regions it could
// explain.
void noteChordError(const Model& model,
                    const DeviationMap& map,
                    const std::vector<int>& faces,
                    const PipelineConfig& config,
                    InspectionResult* result) {
  const ChordError& chord = model.chordError();
  if (!(chord.max > 0.0) || chord.face.size() != model.mesh().faces.size()) {
    return;
  }
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (map.defect[i] >= 0 && faces[i] >= 0) {
      DefectRegion& region = result->defects[static_cast<std::size_t>(map.defect[i])];
      region.cad_chord_error =
          std::max(region.cad_chord_error, chord.face[static_cast<std::size_t>(faces[i])]);
    }
  }
  const double band = std::min(config.tolerance.upper, -config.tolerance.lower);
  if (!(chord.max > 0.1 * band)) {
    return;
  }
  const Eigen::Vector3d& at = chord.max_at;
  char where[96];
  std::snprintf(where, sizeof(where), "(%.4g, %.4g, %.4g) m", at.x(), at.y(), at.z());
  result->warnings.push_back(
      "the CAD's faces may lie up to " + formatLength(chord.max) +
      " from the curved surface they stand for (its chord error, estimated from the turns "
      "between them; largest at " +
      where +
      "), more than a tenth of the tolerance band: "
      "deviations there measure the tessellation as well as the part; export the CAD with a "
      "finer chord tolerance");
  const auto explained =
      std::count_if(result->defects.begin(), result->defects.end(), [](const DefectRegion& region) {
        return region.cad_chord_error >= 0.5 * std::abs(region.peak);
      });
  if (explained > 0) {
    result->warnings.push_back(std::to_string(explained) + " of " +
                               std::to_string(result->defects.size()) +
                               " defect region(s) lie on CAD faces whose chord error is at "
                               "least half their peak: they may be the CAD's facets, not the "
                               "part (defects[].cad_chord_error)");
  }
}

}  // namespace

// Deviation, statistics, shape deviation and defect regions of a registered scan.
void measurePart(const Model& model,
                 const Scan& scan,
                 const Points& point_normals,
                 const DescriptorResult& descriptors,
                 const PipelineConfig& config,
                 InspectionResult* result) {
  DeviationMap& map = result->deviation_map;
  map.points.resize(scan.points.size());
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    map.points[i] = result->T_cad_scan * scan.points[i];
  }
  Points normals_cad;
  normals_cad.reserve(point_normals.size());
  for (const Eigen::Vector3d& normal : point_normals) {
    normals_cad.push_back(result->T_cad_scan.linear() * normal);
  }
  const double diagonal = model.bounds().diagonal();
  SurfaceDistances distances = measureDeviation(model,
                                                map.points,
                                                config.deviation.max_distance_ratio * diagonal,
                                                normals_cad,
                                                config.deviation.facing_tolerance_deg);
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
  // Each point is judged where it meets the CAD: against its region's band, or not at all on a
  // region left out (its deviation stays in the map, measured).
  if (!config.regions.empty()) {
    map.region = regionOf(config.regions, distances.closest);
  }
  const ToleranceBands bands = toleranceBands(config.regions, map.region, config.tolerance);
  std::size_t excluded = 0;
  const std::vector<float> judged = judgedDeviation(config.regions, map, &excluded);
  result->deviation = summarizeDeviation(judged, bands, config.deviation.histogram_bins);
  result->deviation.excluded = excluded;
  result->deviation.unmatched -= excluded;
  summarizeShapeDeviation(map.shape_deviation, &result->deviation);
  const std::vector<bool> covered =
      coveredCells(model, map.points, config.deviation.coverage_distance_cells * model.cellSize());
  const std::vector<int> cell_region =
      regionOf(config.regions, model.descriptors().graph.centroids);
  result->deviation.coverage =
      coveredShare(model, covered, evaluatedCells(config.regions, cell_region));
  // One neighbourhood for the band and, with a measurement uncertainty, its two guard bands.
  DefectNeighbourhood surface(map.points, scan.faces);
  DefectResult defects = findDefects(surface, judged, bands, config.defects);
  result->defects = std::move(defects.regions);
  map.defect = std::move(defects.point_region);
  result->regions =
      summarizeRegions(model, config, map, bands, covered, cell_region, result->defects);
  result->conformance = conformanceZones(judged, surface, bands, config, &result->regions);
  noteChordError(model, map, distances.faces, config, result);
  // Read only where they will be judged (judgeComparisonPoints lists the rest as not evaluated).
  if (judgedPose(*result)) {
    result->comparison_points = readComparisonPoints(config.comparison_points,
                                                     config.regions,
                                                     config.tolerance,
                                                     model.query(),
                                                     map,
                                                     model.cellSize());
  }
  result->scan_faces = scan.faces;
  // A band narrower than the residual noise of the fit flags scattered points, not the part. At
  // a fixed pose the residual holds the part's offset from the pose too: the scan's own noise.
  const double band = std::min(config.tolerance.upper, -config.tolerance.lower);
  const bool fixed = result->registration == RegistrationStatus::kFixed;
  const double noise = fixed ? result->scan_noise : result->noise_sigma;
  if (std::isfinite(noise) && band < 3.0 * noise) {
    result->warnings.push_back(
        "the tolerance band (" + formatLength(config.tolerance.lower) + " to " +
        formatLength(config.tolerance.upper) + ") is narrower than 3x " +
        (fixed ? "the scan's own noise" : "the fit's residual noise") + " (sigma " +
        formatLength(noise) + "): scattered points fall outside it by noise alone");
  }
}

namespace {

// The part's verdict, kept apart from how sure the registration is.
void judgePart(const PipelineConfig& config, InspectionResult* result) {
  const DeviationStatistics& stats = result->deviation;
  const bool own_bands =
      std::any_of(config.regions.begin(), config.regions.end(), [](const RegionConfig& region) {
        return region.has_tolerance;
      });
  const std::string band = "[" + formatLength(config.tolerance.lower) + ", " +
                           formatLength(config.tolerance.upper) + "]" +
                           (own_bands ? " (named regions: their own)" : "");
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
  const DatumAlignment& datums = result->datum_alignment;
  if (datums.requested && !datums.aligned && result->registration == RegistrationStatus::kOk) {
    result->verdict_reason = "not evaluated: no datum alignment (" + datums.message +
                             "); the deviation shown is the best fit's";
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
  if (result->conformance.measurement_uncertainty > 0.0) {
    judgeWithUncertainty(config, result);
    return;
  }
  if (!result->defects.empty()) {
    result->verdict = Verdict::kFail;
    result->verdict_reason = std::to_string(result->defects.size()) +
                             " region(s) outside the tolerance band " + band +
                             "; largest: " + describeDefect(result->defects.front(), *result);
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
  result->verdict_reason =
      "no region of " + regionSize(config.defects) + " outside the tolerance band " + band + "; " +
      std::to_string(stats.in_tolerance_fraction) + " of " + std::to_string(stats.evaluated) +
      " points inside it, deviation " + formatLength(stats.min) + " to " + formatLength(stats.max);
}

// Each comparison point's verdict; one that fails fails the part, one not shown or within the
// measurement uncertainty of a limit leaves a part that would pass not evaluated.
void judgeComparisonPoints(const PipelineConfig& config, InspectionResult* result) {
  const bool posed =
      judgedPose(*result) && result->comparison_points.size() == config.comparison_points.size();
  if (!posed) {
    const std::string why = "not evaluated: the part is not (" + result->verdict_reason + ")";
    result->comparison_points.clear();
    for (const ComparisonPointConfig& point : config.comparison_points) {
      ComparisonPointResult unread;
      unread.name = point.name;
      unread.datum = point.datum;
      unread.tolerance = point.tolerance;
      unread.verdict_reason = why;
      result->comparison_points.push_back(unread);
    }
    return;
  }
  const ComparisonPointResult* failed = nullptr;
  const ComparisonPointResult* undecided = nullptr;
  for (ComparisonPointResult& point : result->comparison_points) {
    judgeComparisonPoint(config.verdict.measurement_uncertainty, &point);
    if (point.verdict == Verdict::kFail && failed == nullptr) {
      failed = &point;
    }
    if (point.verdict == Verdict::kNotEvaluated && undecided == nullptr) {
      undecided = &point;
    }
  }
  if (failed != nullptr && result->verdict != Verdict::kFail) {
    result->verdict = Verdict::kFail;
    result->verdict_reason =
        "comparison point '" + failed->name + "' fails: " + failed->verdict_reason;
  } else if (undecided != nullptr && result->verdict == Verdict::kPass) {
    result->verdict = Verdict::kNotEvaluated;
    result->verdict_reason = "not evaluated: comparison point '" + undecided->name +
                             "': " + withoutNotEvaluated(undecided->verdict_reason);
  }
}

}  // namespace

bool judgedPose(const InspectionResult& result) {
  const bool datums_missed = result.datum_alignment.requested && !result.datum_alignment.aligned &&
                             result.registration == RegistrationStatus::kOk;
  return result.status.code != StatusCode::kCancelled && !datums_missed &&
         (result.registration == RegistrationStatus::kOk ||
          result.registration == RegistrationStatus::kFixed);
}

std::string withoutNotEvaluated(const std::string& reason) {
  const std::string prefix = "not evaluated: ";
  return reason.rfind(prefix, 0) == 0 ? reason.substr(prefix.size()) : reason;
}

void judge(const PipelineConfig& config, InspectionResult* result) {
  judgePart(config, result);
  judgeRegions(config, result);
  judgeComparisonPoints(config, result);
}

}  // namespace freeform_inspection::internal
