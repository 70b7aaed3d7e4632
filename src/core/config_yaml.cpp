// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/config_yaml.h"

#include <fstream>
#include <map>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "freeform_inspection/config_fields.h"

namespace freeform_inspection {
namespace {

// Flattens nested maps into "section/name" → scalar node, reporting non-map structure.
void flatten(const YAML::Node& node,
             const std::string& prefix,
             std::map<std::string, YAML::Node>* leaves,
             std::vector<std::string>* errors) {
  for (const auto& entry : node) {
    const std::string key = prefix + entry.first.as<std::string>();
    if (entry.second.IsMap()) {
      flatten(entry.second, key + "/", leaves, errors);
    } else if (entry.second.IsScalar() || entry.second.IsSequence()) {
      (*leaves)[key] = entry.second;  // whether a list is wanted there is the field's to say
    } else {
      errors->push_back("'" + key + "' must be a value or a list");
    }
  }
}

struct Assign {
  const YAML::Node& value;
  void operator()(double* target) const { *target = value.as<double>(); }
  void operator()(bool* target) const { *target = value.as<bool>(); }
  void operator()(int* target) const { *target = value.as<int>(); }
  void operator()(std::vector<double>* target) const {
    if (!value.IsSequence()) {
      throw YAML::BadConversion(value.Mark());
    }
    *target = value.as<std::vector<double>>();
  }
  void operator()(std::size_t* target) const {
    const long long parsed = value.as<long long>();
    if (parsed < 0) {
      throw YAML::BadConversion(value.Mark());
    }
    *target = static_cast<std::size_t>(parsed);
  }
};

}  // namespace

ConfigLoadResult parsePipelineConfig(const std::string& yaml_text) {
  ConfigLoadResult result;
  std::vector<std::string> errors;
  std::map<std::string, YAML::Node> leaves;
  try {
    const YAML::Node root = YAML::Load(yaml_text);
    if (root.IsMap()) {
      flatten(root, "", &leaves, &errors);
    } else if (!root.IsNull()) {
      errors.push_back("configuration must be a map of sections");
    }
  } catch (const YAML::Exception& e) {
    errors.push_back(std::string("YAML syntax error: ") + e.what());
  }
  for (const auto& field : configFields(result.config)) {
    const auto leaf = leaves.find(field.key);
    if (leaf == leaves.end()) {
      continue;
    }
    try {
      std::visit(Assign{leaf->second}, field.target);
    } catch (const YAML::Exception&) {
      errors.push_back("'" + field.key +
                       "' has a value of the wrong type: " + YAML::Dump(leaf->second));
    }
    leaves.erase(leaf);
  }
  for (const auto& unknown : leaves) {
    errors.push_back("unknown key '" + unknown.first + "'");
  }
  for (const auto& e : validate(result.config)) {
    errors.push_back(e);
  }
  if (!errors.empty()) {
    result.status = Status::failure(StatusCode::kInvalidInput, joinMessages(errors));
  }
  return result;
}

ConfigLoadResult loadPipelineConfigFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) {
    ConfigLoadResult result;
    result.status =
        Status::failure(StatusCode::kInvalidInput, "cannot open configuration '" + path + "'");
    return result;
  }
  std::stringstream text;
  text << file.rdbuf();
  ConfigLoadResult result = parsePipelineConfig(text.str());
  if (!result.status.ok()) {
    result.status.message = "configuration '" + path + "': " + result.status.message;
  }
  return result;
}

}  // namespace freeform_inspection
