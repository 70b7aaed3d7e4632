// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "report_json.h"

#include <cmath>

namespace freeform_inspection {
namespace {

nlohmann::json matrixRows(const Eigen::Isometry3d& transform) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) {
    rows.push_back({transform(r, 0), transform(r, 1), transform(r, 2), transform(r, 3)});
  }
  return rows;
}

// JSON has no NaN: an unknown number is null.
nlohmann::json numberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json deviationJson(const DeviationStatistics& d) {
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
          {"unmatched", d.unmatched}};
}

nlohmann::json defectsJson(const std::vector<DefectRegion>& defects) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& d : defects) {
    list.push_back({{"centroid", {d.centroid.x(), d.centroid.y(), d.centroid.z()}},
                    {"points", d.points},
                    {"area", d.area},
                    {"peak", d.peak}});
  }
  return list;
}

nlohmann::json countsJson(const InspectionCounts& c) {
  return {{"scan_points", c.scan_points},
          {"non_finite", c.non_finite},
          {"cad_vertices", c.cad_vertices},
          {"features", c.features},
          {"candidates", c.candidates},
          {"correspondences", c.correspondences}};
}

}  // namespace

nlohmann::json toJson(const InspectionResult& result) {
  nlohmann::json json;
  json["status"] = toString(result.registration);
  json["message"] = result.status.ok() ? "" : result.status.message;
  json["error_code"] = toString(result.status.code);
  json["transform_cad_from_scan"] = matrixRows(result.T_cad_scan);
  json["alternatives"] = nlohmann::json::array();
  for (const auto& alternative : result.alternatives) {
    json["alternatives"].push_back(matrixRows(alternative));
  }
  json["rmse"] = numberOrNull(result.rmse);
  json["fitness"] = result.fitness;
  json["verdict"] = toString(result.verdict);
  json["deviation"] = deviationJson(result.deviation);
  json["defects"] = defectsJson(result.defects);
  json["counts"] = countsJson(result.counts);
  json["timings_s"] = nlohmann::json::object();
  for (const auto& timing : result.timings) {
    json["timings_s"][timing.stage] = timing.seconds;
  }
  json["warnings"] = result.warnings;
  return json;
}

}  // namespace freeform_inspection
