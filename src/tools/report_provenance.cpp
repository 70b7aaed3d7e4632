// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "report_provenance.h"

#include <charconv>
#include <cstdio>
#include <fstream>
#include <type_traits>
#include <variant>

#include "freeform_inspection/config_fields.h"
#include "freeform_inspection/content_hash.h"
#include "freeform_inspection/datum_alignment.h"

namespace freeform_inspection {
namespace {

// The shortest text that reads back to the same double.
std::string numberText(double value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof(text), value, std::chars_format::general).ptr;
  return std::string(text, end);
}

std::string valueText(const ConfigField& field) {
  return std::visit(
      [](const auto* target) -> std::string {
        using T = std::decay_t<decltype(*target)>;
        if constexpr (std::is_same_v<T, bool>) {
          return *target ? "true" : "false";
        } else if constexpr (std::is_same_v<T, double>) {
          return numberText(*target);
        } else if constexpr (std::is_same_v<T, std::vector<double>>) {
          std::string list = "[";
          for (std::size_t i = 0; i < target->size(); ++i) {
            list += (i == 0 ? "" : ", ") + numberText((*target)[i]);
          }
          return list + "]";
        } else {
          return std::to_string(*target);
        }
      },
      field.target);
}

}  // namespace

std::string fileHash(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    return "unreadable";
  }
  ContentHash hash;
  char buffer[1 << 16];
  while (file.read(buffer, sizeof(buffer)) || file.gcount() > 0) {
    hash.addBytes(buffer, static_cast<std::size_t>(file.gcount()));
  }
  return file.eof() ? hash.hex() : "unreadable";
}

std::vector<std::pair<std::string, std::string>> configEntries(const PipelineConfig& config) {
  PipelineConfig copy = config;  // configFields() hands out writable pointers
  std::vector<std::pair<std::string, std::string>> entries;
  for (const ConfigField& field : configFields(copy)) {
    entries.emplace_back(field.key, valueText(field));
  }
  // The regions and comparison points judge the part as much as the fields do: they are in the
  // hash too.
  const auto point = [](const Eigen::Vector3d& p) {
    return "[" + numberText(p.x()) + ", " + numberText(p.y()) + ", " + numberText(p.z()) + "]";
  };
  for (const RegionConfig& region : config.regions) {
    std::string text;
    for (const RegionBox& box : region.boxes) {
      text += "box " + point(box.min) + " to " + point(box.max) + "; ";
    }
    if (region.has_tolerance) {
      text += "tolerance " + numberText(region.tolerance.lower) + " to " +
              numberText(region.tolerance.upper) + "; ";
    }
    text += std::string("evaluate ") + (region.evaluate ? "true" : "false") + "; align " +
            (region.align ? "true" : "false") + "; min_coverage " + numberText(region.min_coverage);
    entries.emplace_back("regions/" + region.name, text);
  }
  // So are the comparison points.
  for (const ComparisonPointConfig& p : config.comparison_points) {
    std::string text = "position " + point(p.position) + "; ";
    if (p.has_tolerance) {
      text += "tolerance " + numberText(p.tolerance.lower) + " to " +
              numberText(p.tolerance.upper) + "; ";
    }
    text += "radius " + numberText(p.radius);
    if (!p.datum.empty()) {
      text += "; datum " + p.datum;  // a datum target moves the frame every deviation is read in
    }
    entries.emplace_back("points/" + p.name, text);
  }
  // The datums' order moves the frame as well when the targets hold an axis twice.
  if (hasDatumTargets(config.comparison_points)) {
    entries.emplace_back("points/datum_precedence",
                         datumPrecedenceText(config.datum_precedence, config.comparison_points));
  }
  return entries;
}

std::string configHash(const PipelineConfig& config) {
  ContentHash hash;
  for (const auto& [key, value] : configEntries(config)) {
    hash.addText(key);
    hash.addText("=");
    hash.addText(value);
    hash.addText("\n");
  }
  return hash.hex();
}

std::string utcTimestamp(std::time_t time) {
  std::tm utc{};
  gmtime_r(&time, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace freeform_inspection
