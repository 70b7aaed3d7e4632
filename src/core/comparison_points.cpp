// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/comparison_points.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "median_internal.h"
#include "pipeline_internal.h"
#include "yaml_file_internal.h"
#include <yaml-cpp/yaml.h>

#include "freeform_inspection/mesh_query.h"

namespace freeform_inspection {
namespace {

// "comparison point 'LE_1'" or, before a name is known, "comparison point 2".
std::string label(const ComparisonPointConfig& point, std::size_t position) {
  return point.name.empty() ? "comparison point " + std::to_string(position + 1)
                            : "comparison point '" + point.name + "'";
}

ComparisonPointConfig parsePoint(const YAML::Node& node, std::size_t position) {
  ComparisonPointConfig point;
  const std::string what = "comparison point " + std::to_string(position + 1);
  if (!node.IsMap()) {
    throw std::runtime_error(what + " must be a map with name and position");
  }
  internal::checkKeys(node, {"name", "position", "tolerance", "radius", "datum"}, what);
  if (node["name"]) {
    point.name = node["name"].as<std::string>();
  }
  const std::string named = label(point, position);
  const YAML::Node place = node["position"];
  if (!place || !place.IsSequence() || place.size() != 3) {
    throw std::runtime_error(named + ": position must be a list of three numbers [m]");
  }
  point.position = {place[0].as<double>(), place[1].as<double>(), place[2].as<double>()};
  if (const YAML::Node tolerance = node["tolerance"]) {
    point.has_tolerance = true;
    point.tolerance = internal::parseTolerance(tolerance, named);
  }
  if (node["radius"]) {
    point.radius = node["radius"].as<double>();
  }
  if (node["datum"]) {
    point.datum = node["datum"].as<std::string>();
    if (point.datum.empty()) {
      throw std::runtime_error(named + ": datum must name a datum (A, B, ...) when given");
    }
  }
  return point;
}

// The `datum_precedence:` beside the points: the datums, primary first, or `none`.
DatumPrecedence parsePrecedence(const YAML::Node& node) {
  DatumPrecedence precedence;
  if (!node) {
    return precedence;
  }
  if (node.IsScalar() && node.as<std::string>() == "none") {
    precedence.alike = true;
    return precedence;
  }
  const std::string expected =
      "datum_precedence must list the datums, primary first ([A, B, C]), or be none";
  if (!node.IsSequence() || node.size() == 0) {
    throw std::runtime_error(expected);
  }
  for (const auto& datum : node) {
    if (!datum.IsScalar()) {
      throw std::runtime_error(expected);
    }
    precedence.order.push_back(datum.as<std::string>());
  }
  return precedence;
}

double standardDeviation(const std::vector<double>& values) {
  double mean = 0.0;
  for (const double v : values) {
    mean += v;
  }
  mean /= static_cast<double>(values.size());
  double squares = 0.0;
  for (const double v : values) {
    squares += (v - mean) * (v - mean);
  }
  return std::sqrt(squares / static_cast<double>(values.size()));
}

}  // namespace

std::vector<std::string> validate(const std::vector<ComparisonPointConfig>& points) {
  std::vector<std::string> errors;
  std::set<std::string> names;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const ComparisonPointConfig& point = points[p];
    const std::string named = label(point, p);
    if (point.name.empty()) {
      errors.push_back(named + " needs a name");
    } else if (!names.insert(point.name).second) {
      errors.push_back(named + " is named twice");
    }
    if (!point.position.allFinite()) {
      errors.push_back(named + ": position must be finite (m)");
    }
    if (!(point.radius >= 0.0) || !std::isfinite(point.radius)) {
      errors.push_back(named + ": radius must be finite and ≥ 0 (m; 0 = the model's cell)");
    }
    if (point.has_tolerance) {
      for (const std::string& message : validate(point.tolerance)) {
        errors.push_back(named + ": " + message);
      }
    }
  }
  return errors;
}

std::vector<std::string> validate(const DatumPrecedence& precedence,
                                  const std::vector<ComparisonPointConfig>& points) {
  std::vector<std::string> errors;
  if (precedence.alike) {
    return errors;
  }
  std::set<std::string> listed;
  for (const std::string& datum : precedence.order) {
    if (datum.empty()) {
      errors.push_back("datum_precedence lists an empty datum");
    } else if (!listed.insert(datum).second) {
      errors.push_back("datum_precedence lists datum '" + datum + "' twice");
    } else if (std::none_of(points.begin(), points.end(), [&](const ComparisonPointConfig& p) {
                 return p.datum == datum;
               })) {
      errors.push_back("datum_precedence lists datum '" + datum +
                       "', which no comparison point is a target of");
    }
  }
  if (precedence.order.empty()) {
    return errors;  // the labels in alphabetical order
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (!points[p].datum.empty() && listed.count(points[p].datum) == 0) {
      errors.push_back(label(points[p], p) + ": datum '" + points[p].datum +
                       "' is not in datum_precedence");
    }
  }
  return errors;
}

ComparisonPointsLoadResult parseComparisonPoints(const std::string& yaml_text) {
  ComparisonPointsLoadResult result;
  result.status = internal::parseYamlList(
      yaml_text,
      "points",
      "comparison points",
      parsePoint,
      [&result](const auto& items) {
        std::vector<std::string> errors = validate(items);
        const std::vector<std::string> order = validate(result.datum_precedence, items);
        errors.insert(errors.end(), order.begin(), order.end());
        return errors;
      },
      &result.points,
      {"datum_precedence"},
      [&result](const YAML::Node& root) {
        result.datum_precedence = parsePrecedence(root["datum_precedence"]);
      });
  if (!result.status.ok()) {
    result.datum_precedence = {};
  }
  return result;
}

ComparisonPointsLoadResult loadComparisonPointsFile(const std::string& path) {
  return internal::parseYamlFile<ComparisonPointsLoadResult>(
      path, "comparison points", parseComparisonPoints);
}

PlacedPoint placeComparisonPoint(const ComparisonPointConfig& point,
                                 const MeshQuery& cad,
                                 double default_radius) {
  PlacedPoint place;
  place.radius = point.radius > 0.0 ? point.radius : default_radius;
  const ClosestPoint closest = cad.closest(point.position);
  if (closest.found) {
    place.found = true;
    place.nominal = closest.point;
    place.normal = closest.normal;
    place.off_surface = closest.distance;
  }
  return place;
}

PlaceReading readAround(const PlacedPoint& place,
                        const Points& points_cad,
                        const std::vector<float>& deviation) {
  const double r2 = place.radius * place.radius;
  std::vector<double> read;
  for (std::size_t i = 0; i < points_cad.size() && i < deviation.size(); ++i) {
    const double d = static_cast<double>(deviation[i]);
    if (!std::isfinite(d)) {
      continue;
    }
    const Eigen::Vector3d foot = points_cad[i] - d * place.normal;
    if ((foot - place.nominal).squaredNorm() <= r2) {
      read.push_back(d);
    }
  }
  PlaceReading reading;
  reading.points = read.size();
  if (reading.measured()) {
    reading.spread = standardDeviation(read);
    reading.deviation = internal::median(std::move(read));
  }
  return reading;
}

std::vector<ComparisonPointResult> readComparisonPoints(
    const std::vector<ComparisonPointConfig>& points,
    const std::vector<RegionConfig>& regions,
    const ToleranceConfig& part_tolerance,
    const MeshQuery& cad,
    const DeviationMap& map,
    double default_radius) {
  std::vector<ComparisonPointResult> results;
  for (const ComparisonPointConfig& config : points) {
    ComparisonPointResult result;
    result.name = config.name;
    result.datum = config.datum;
    result.tolerance = config.tolerance;
    const PlacedPoint place = placeComparisonPoint(config, cad, default_radius);
    result.radius = place.radius;
    if (!place.found) {
      result.verdict_reason = "not evaluated: no CAD surface to place it on";
      results.push_back(result);
      continue;
    }
    result.nominal = place.nominal;
    result.normal = place.normal;
    result.off_surface = place.off_surface;
    if (!config.has_tolerance) {
      const int region = regionOf(regions, {place.nominal}).front();
      result.tolerance = regionTolerance(regions, region, part_tolerance);
    }
    if (!place.near_surface()) {
      result.verdict_reason = "not evaluated: its position lies " +
                              internal::formatLength(result.off_surface) +
                              " off the CAD surface (a position in other units or another frame?)";
      results.push_back(result);
      continue;
    }
    const PlaceReading reading = readAround(place, map.points, map.deviation);
    result.points = reading.points;
    if (!reading.measured()) {
      result.verdict_reason = "not evaluated: " + std::to_string(reading.points) +
                              " scan point(s) within " + internal::formatLength(result.radius) +
                              " of it, " + std::to_string(kMinComparisonPoints) + " needed";
      results.push_back(result);
      continue;
    }
    result.spread = reading.spread;
    result.deviation = reading.deviation;
    results.push_back(result);
  }
  return results;
}

void judgeComparisonPoint(double measurement_uncertainty, ComparisonPointResult* point) {
  if (!point->measured()) {
    point->verdict = Verdict::kNotEvaluated;
    return;
  }
  const double u = std::max(0.0, measurement_uncertainty);
  const double d = point->deviation;
  const ToleranceConfig& band = point->tolerance;
  const std::string text = internal::formatLength(d);
  const std::string limits =
      "[" + internal::formatLength(band.lower) + ", " + internal::formatLength(band.upper) + "]";
  if (d < band.lower - u || d > band.upper + u) {
    point->verdict = Verdict::kFail;
    point->verdict_reason = "deviation " + text + " outside its band " + limits +
                            (u > 0.0 ? " widened by the measurement uncertainty" : "");
  } else if (d < band.lower + u || d > band.upper - u) {
    point->verdict = Verdict::kNotEvaluated;
    point->verdict_reason = "not evaluated: deviation " + text + " inside its band " + limits +
                            " but within the measurement uncertainty of a limit (ISO 14253-1)";
  } else {
    point->verdict = Verdict::kPass;
    point->verdict_reason = "deviation " + text + " inside its band " + limits;
  }
}

}  // namespace freeform_inspection
