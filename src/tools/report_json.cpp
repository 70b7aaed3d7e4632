// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "report_json.h"

#include <cmath>

namespace freeform_inspection {
namespace {

nlohmann::ordered_json matrixRows(const Eigen::Isometry3d& transform) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (int r = 0; r < 4; ++r) {
    rows.push_back({transform(r, 0), transform(r, 1), transform(r, 2), transform(r, 3)});
  }
  return rows;
}

// JSON has no NaN: an unknown number is null.
nlohmann::ordered_json numberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json vectorJson(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

// Bin edges [m] (one more than the counts) and points per bin; empty lists when not measured.
nlohmann::ordered_json histogramJson(const DeviationStatistics& d) {
  return {{"edges", d.histogram_edges}, {"counts", d.histogram_counts}};
}

nlohmann::ordered_json deviationJson(const DeviationStatistics& d) {
  if (d.evaluated == 0) {
    // Nothing was measured: null, not zeros that read like a perfect part.
    nlohmann::ordered_json none;
    for (const char* key : {"mean",
                            "std",
                            "rms",
                            "min",
                            "max",
                            "p5",
                            "p50",
                            "p95",
                            "in_tolerance_fraction",
                            "coverage",
                            "shape_mean",
                            "shape_p95"}) {
      none[key] = nullptr;
    }
    none["evaluated"] = 0;
    none["unmatched"] = d.unmatched;
    none["excluded"] = d.excluded;
    none["histogram"] = histogramJson(d);
    return none;
  }
  return {{"mean", d.mean},
          {"std", d.std},
          {"rms", d.rms},
          {"min", d.min},
          {"max", d.max},
          {"p5", d.p5},
          {"p50", d.p50},
          {"p95", d.p95},
          {"in_tolerance_fraction", d.in_tolerance_fraction},
          {"coverage", d.coverage},
          {"evaluated", d.evaluated},
          {"unmatched", d.unmatched},
          {"excluded", d.excluded},
          {"shape_mean", numberOrNull(d.shape_mean)},
          {"shape_p95", numberOrNull(d.shape_p95)},
          {"histogram", histogramJson(d)}};
}

// The named region a defect lies in, null for the rest of the part.
nlohmann::ordered_json regionName(const InspectionResult& result, int region) {
  const std::string name = result.regionName(region);
  return name.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(name);
}

nlohmann::ordered_json defectsJson(const InspectionResult& result) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const auto& d : result.defects) {
    list.push_back({{"centroid", vectorJson(d.centroid)},
                    {"points", d.points},
                    {"area", d.area},
                    {"peak", d.peak},
                    {"sign", d.sign},
                    {"mean", d.mean},
                    {"bbox_min", vectorJson(d.bbox_min)},
                    {"bbox_max", vectorJson(d.bbox_max)},
                    {"cad_chord_error", d.cad_chord_error},
                    {"region", regionName(result, d.region)}});
  }
  return list;
}

nlohmann::ordered_json regionsJson(const std::vector<RegionResult>& regions) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const RegionResult& r : regions) {
    list.push_back({{"name", r.name},
                    {"evaluated", r.evaluated},
                    {"tolerance", {{"upper", r.tolerance.upper}, {"lower", r.tolerance.lower}}},
                    {"verdict", toString(r.verdict)},
                    {"verdict_reason", r.verdict_reason},
                    {"defects", r.defects},
                    {"deviation", deviationJson(r.deviation)}});
  }
  return list;
}

nlohmann::ordered_json comparisonPointsJson(const std::vector<ComparisonPointResult>& points) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const ComparisonPointResult& p : points) {
    list.push_back({{"name", p.name},
                    {"nominal", vectorJson(p.nominal)},
                    {"normal", vectorJson(p.normal)},
                    {"off_surface", p.off_surface},
                    {"radius", p.radius},
                    {"tolerance", {{"upper", p.tolerance.upper}, {"lower", p.tolerance.lower}}},
                    {"points", p.points},
                    {"deviation", numberOrNull(p.deviation)},
                    {"spread", numberOrNull(p.spread)},
                    {"verdict", toString(p.verdict)},
                    {"verdict_reason", p.verdict_reason}});
    if (!p.datum.empty()) {
      list.back()["datum"] = p.datum;
    }
  }
  return list;
}

// The frame the datum targets fix (datum_alignment.h); null when no comparison point names a
// datum.
nlohmann::ordered_json datumAlignmentJson(const DatumAlignment& a) {
  if (!a.requested) {
    return nullptr;
  }
  nlohmann::ordered_json targets = nlohmann::ordered_json::array();
  for (const DatumTargetReading& t : a.targets) {
    targets.push_back({{"name", t.name},
                       {"datum", t.datum},
                       {"nominal", vectorJson(t.nominal)},
                       {"normal", vectorJson(t.normal)},
                       {"points", t.points},
                       {"deviation_best_fit", numberOrNull(t.best_fit)},
                       {"deviation_aligned", numberOrNull(t.aligned)}});
  }
  return {{"aligned", a.aligned},
          {"message", a.message},
          {"transform_cad_from_scan_best_fit", matrixRows(a.T_cad_scan_best_fit)},
          {"rotation_from_best_fit_deg", numberOrNull(a.turn_deg)},
          {"translation_from_best_fit", numberOrNull(a.shift)},
          {"rounds", a.rounds},
          {"precedence", a.precedence},
          {"conditioning", numberOrNull(a.conditioning)},
          {"rotation_std_deg", numberOrNull(a.rotation_std_deg)},
          {"translation_std", numberOrNull(a.translation_std)},
          {"targets", targets}};
}

// The part's pose in the scan frame, as geometry_msgs/PoseWithCovariance orders it.
nlohmann::ordered_json poseUncertaintyJson(const PoseUncertainty& u) {
  if (!u.known) {
    return nullptr;
  }
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (int r = 0; r < 6; ++r) {
    nlohmann::ordered_json row = nlohmann::ordered_json::array();
    for (int c = 0; c < 6; ++c) {
      row.push_back(u.covariance(r, c));
    }
    rows.push_back(row);
  }
  return {{"rotation_deg", numberOrNull(u.rotation_deg)},
          {"translation", numberOrNull(u.translation)},
          {"constrained", u.constrained},
          {"points", u.points},
          {"covariance", rows}};
}

// The guard bands of ISO 14253-1's decision rule; null when no measurement uncertainty is set.
nlohmann::ordered_json conformanceJson(const ConformanceZones& z) {
  if (!(z.measurement_uncertainty > 0.0)) {
    return nullptr;
  }
  return {{"rule", "ISO 14253-1"},
          {"measurement_uncertainty", z.measurement_uncertainty},
          {"acceptance_zone", {z.acceptance_lower, z.acceptance_upper}},
          {"rejection_limits", {z.rejection_lower, z.rejection_upper}},
          {"regions_outside_acceptance", z.regions_outside_acceptance},
          {"regions_beyond_rejection", z.regions_beyond_rejection},
          {"inside_acceptance_fraction", z.inside_acceptance_fraction},
          {"inside_rejection_fraction", z.inside_rejection_fraction}};
}

nlohmann::ordered_json countsJson(const InspectionCounts& c) {
  return {{"scan_points", c.scan_points},
          {"non_finite", c.non_finite},
          {"cropped", c.cropped},
          {"support_points", c.support_points},
          {"scan_faces", c.scan_faces},
          {"cad_vertices", c.cad_vertices},
          {"features", c.features},
          {"candidates", c.candidates},
          {"correspondences", c.correspondences}};
}

}  // namespace

nlohmann::ordered_json toJson(const InspectionResult& result) {
  nlohmann::ordered_json json;
  json["status"] = toString(result.registration);
  json["message"] = result.status.message;
  json["error_code"] = toString(result.status.code);
  json["transform_cad_from_scan"] = matrixRows(result.T_cad_scan);
  json["alternatives"] = nlohmann::ordered_json::array();
  for (const auto& alternative : result.alternatives) {
    json["alternatives"].push_back(matrixRows(alternative));
  }
  json["rmse"] = numberOrNull(result.rmse);
  json["fitness"] = result.fitness;
  json["score"] = result.score;
  json["ambiguity"] = result.ambiguity;
  json["noise_sigma"] = numberOrNull(result.noise_sigma);
  json["inlier_distance"] = numberOrNull(result.inlier_distance);
  json["scan_noise"] = numberOrNull(result.scan_noise);
  json["surface_on_cad"] = numberOrNull(result.surface_on_cad);
  json["cad_curve_share"] = result.cad_curve_share;
  json["offset_from_initial"] = {{"rotation_deg", numberOrNull(result.offset_from_initial_deg)},
                                 {"translation", numberOrNull(result.offset_from_initial)}};
  json["pose_uncertainty"] = poseUncertaintyJson(result.pose_uncertainty);
  json["verdict"] = toString(result.verdict);
  json["verdict_reason"] = result.verdict_reason;
  json["deviation"] = deviationJson(result.deviation);
  json["defects"] = defectsJson(result);
  json["regions"] = regionsJson(result.regions);
  json["comparison_points"] = comparisonPointsJson(result.comparison_points);
  json["datum_alignment"] = datumAlignmentJson(result.datum_alignment);
  json["conformance"] = conformanceJson(result.conformance);
  json["counts"] = countsJson(result.counts);
  json["timings_s"] = nlohmann::ordered_json::object();
  for (const auto& timing : result.timings) {
    json["timings_s"][timing.stage] = timing.seconds;
  }
  json["warnings"] = result.warnings;
  return json;
}

}  // namespace freeform_inspection
