// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

// Internal to the core library: what the YAML files of an inspection plan (regions.h,
// comparison_points.h) share. Not installed.

#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/file_util.h"
#include <yaml-cpp/yaml.h>

#include "freeform_inspection/deviation.h"
#include "freeform_inspection/types.h"

namespace freeform_inspection::internal {

/// @brief Throws std::runtime_error naming `what` and the key for a key of `map` outside
/// `known`: a misspelt key silently ignored is a wrong inspection.
inline void checkKeys(const YAML::Node& map,
                      const std::set<std::string>& known,
                      const std::string& what) {
  for (const auto& entry : map) {
    const std::string key = entry.first.as<std::string>();
    if (known.count(key) == 0) {
      throw std::runtime_error(what + " has an unknown key '" + key + "'");
    }
  }
}

/// @brief The band of a `tolerance: {upper: +m, lower: -m}` map; throws std::runtime_error
/// naming `named` when it is not one.
inline ToleranceConfig parseTolerance(const YAML::Node& tolerance, const std::string& named) {
  if (!tolerance.IsMap() || !tolerance["upper"] || !tolerance["lower"]) {
    throw std::runtime_error(named + ": tolerance must be a map {upper: +m, lower: -m}");
  }
  checkKeys(tolerance, {"upper", "lower"}, named + "'s tolerance");
  ToleranceConfig band;
  band.upper = tolerance["upper"].as<double>();
  band.lower = tolerance["lower"].as<double>();
  return band;
}

/// @brief The items of the list under `key` of a file's YAML text, each read by
/// `parse_item(node, position)` (which throws std::runtime_error naming what is wrong) and then
/// checked by `check(items)` (messages); any problem empties the list and gives kInvalidInput
/// "invalid <kind>: <messages>". A file holds the list and nothing else but `other_keys`, which
/// `read_other_keys(root)` reads before the list (throwing std::runtime_error as parse_item).
template <typename Item, typename ParseItem, typename Check>
Status parseYamlList(const std::string& yaml_text,
                     const std::string& key,
                     const std::string& kind,
                     ParseItem parse_item,
                     Check check,
                     std::vector<Item>* items,
                     std::set<std::string> other_keys = {},
                     const std::function<void(const YAML::Node&)>& read_other_keys = nullptr) {
  std::vector<std::string> errors;
  try {
    const YAML::Node root = YAML::Load(yaml_text);
    if (!root.IsMap() || !root[key] || !root[key].IsSequence()) {
      errors.push_back("a " + kind + " file must hold a list under '" + key + ":'");
    } else {
      other_keys.insert(key);
      checkKeys(root, other_keys, "the " + kind + " file");
      if (read_other_keys) {
        read_other_keys(root);
      }
      std::size_t position = 0;
      for (const auto& node : root[key]) {
        items->push_back(parse_item(node, position++));
      }
    }
  } catch (const YAML::Exception& e) {
    errors.push_back(std::string("YAML error: ") + e.what());
  } catch (const std::runtime_error& e) {
    errors.push_back(e.what());
  }
  if (errors.empty()) {
    errors = check(*items);
  }
  if (errors.empty()) {
    return Status::success();
  }
  items->clear();
  return Status::failure(StatusCode::kInvalidInput,
                         "invalid " + kind + ": " + joinMessages(errors));
}

/// @brief `parse` (a function of the YAML text returning a result with a `status`) of the file
/// at `path`; an unreadable file is kInvalidInput naming it, and every message starts with
/// "<kind> file '<path>': ".
template <typename Result, typename Parse>
Result parseYamlFile(const std::string& path, const std::string& kind, Parse parse) {
  io_internal::FileBytes bytes;
  const Status read = io_internal::readWholeFile(path, &bytes);
  if (!read.ok()) {
    Result result;
    result.status = Status::failure(read.code, kind + " file: " + read.message);
    return result;
  }
  Result result = parse(std::string(bytes.view()));
  if (!result.status.ok()) {
    result.status.message = kind + " file '" + path + "': " + result.status.message;
  }
  return result;
}

}  // namespace freeform_inspection::internal
