// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/regions.h"

#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>

#include "yaml_file_internal.h"
#include <yaml-cpp/yaml.h>

namespace freeform_inspection {
namespace {

// "region 'root'" or, before a name is known, "region 2".
std::string label(const RegionConfig& region, std::size_t position) {
  return region.name.empty() ? "region " + std::to_string(position + 1)
                             : "region '" + region.name + "'";
}

Eigen::Vector3d corner(const YAML::Node& node, const std::string& what) {
  if (!node.IsSequence() || node.size() != 3) {
    throw std::runtime_error(what + " must be a list of three numbers [m]");
  }
  return {node[0].as<double>(), node[1].as<double>(), node[2].as<double>()};
}

RegionConfig parseRegion(const YAML::Node& node, std::size_t position) {
  RegionConfig region;
  const std::string what = "region " + std::to_string(position + 1);
  if (!node.IsMap()) {
    throw std::runtime_error(what + " must be a map with name and boxes");
  }
  internal::checkKeys(
      node, {"name", "boxes", "tolerance", "evaluate", "align", "min_coverage"}, what);
  if (node["name"]) {
    region.name = node["name"].as<std::string>();
  }
  const std::string named = label(region, position);
  const YAML::Node boxes = node["boxes"] ? node["boxes"] : YAML::Node(YAML::NodeType::Sequence);
  if (!boxes.IsSequence()) {
    throw std::runtime_error(named + ": boxes must be a list of {min: [x, y, z], max: [x, y, z]}");
  }
  for (const auto& box : boxes) {
    if (!box.IsMap()) {
      throw std::runtime_error(named + ": each box must be a map {min: [x, y, z], max: [x, y, z]}");
    }
    internal::checkKeys(box, {"min", "max"}, named + "'s box");
    region.boxes.push_back(
        {corner(box["min"], named + "'s box min"), corner(box["max"], named + "'s box max")});
  }
  if (const YAML::Node tolerance = node["tolerance"]) {
    region.has_tolerance = true;
    region.tolerance = internal::parseTolerance(tolerance, named);
  }
  if (node["evaluate"]) {
    region.evaluate = node["evaluate"].as<bool>();
  }
  if (node["align"]) {
    region.align = node["align"].as<bool>();
  }
  if (node["min_coverage"]) {
    region.min_coverage = node["min_coverage"].as<double>();
  }
  return region;
}

}  // namespace

std::vector<std::string> validate(const std::vector<RegionConfig>& regions) {
  std::vector<std::string> errors;
  std::set<std::string> names;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    const RegionConfig& region = regions[r];
    const std::string named = label(region, r);
    if (region.name.empty()) {
      errors.push_back(named + " needs a name");
    } else if (!names.insert(region.name).second) {
      errors.push_back(named + " is named twice");
    }
    if (region.boxes.empty()) {
      errors.push_back(named + " needs at least one box");
    }
    for (const RegionBox& box : region.boxes) {
      if (!box.min.allFinite() || !box.max.allFinite() ||
          !(box.min.array() <= box.max.array()).all()) {
        errors.push_back(named + " has a box whose min is not ≤ its max in x, y and z (finite, m)");
      }
    }
    if (region.has_tolerance) {
      for (const std::string& message : validate(region.tolerance)) {
        errors.push_back(named + ": " + message);
      }
    }
    if (!(region.min_coverage >= 0.0 && region.min_coverage <= 1.0)) {
      errors.push_back(named + ": min_coverage must be in [0, 1]");
    }
  }
  return errors;
}

RegionsLoadResult parseRegions(const std::string& yaml_text) {
  RegionsLoadResult result;
  result.status = internal::parseYamlList(
      yaml_text,
      "regions",
      "regions",
      parseRegion,
      [](const auto& items) { return validate(items); },
      &result.regions);
  return result;
}

RegionsLoadResult loadRegionsFile(const std::string& path) {
  return internal::parseYamlFile<RegionsLoadResult>(path, "regions", parseRegions);
}

std::vector<int> regionOf(const std::vector<RegionConfig>& regions, const Points& places) {
  std::vector<int> region(places.size(), -1);
  if (regions.empty()) {
    return region;
  }
  for (std::size_t i = 0; i < places.size(); ++i) {
    if (!places[i].allFinite()) {
      continue;
    }
    for (std::size_t r = 0; r < regions.size() && region[i] < 0; ++r) {
      for (const RegionBox& box : regions[r].boxes) {
        if (box.contains(places[i])) {
          region[i] = static_cast<int>(r);
          break;
        }
      }
    }
  }
  return region;
}

ToleranceConfig regionTolerance(const std::vector<RegionConfig>& regions,
                                int region,
                                const ToleranceConfig& part_tolerance) {
  if (region < 0 || static_cast<std::size_t>(region) >= regions.size()) {
    return part_tolerance;
  }
  const RegionConfig& config = regions[static_cast<std::size_t>(region)];
  return config.has_tolerance ? config.tolerance : part_tolerance;
}

ToleranceBands toleranceBands(const std::vector<RegionConfig>& regions,
                              std::vector<int> region_of,
                              const ToleranceConfig& part_tolerance) {
  ToleranceBands bands(part_tolerance);
  for (int r = 0; r < static_cast<int>(regions.size()); ++r) {
    bands.region_bands.push_back(regionTolerance(regions, r, part_tolerance));
  }
  bands.region_of = std::move(region_of);
  return bands;
}

}  // namespace freeform_inspection
