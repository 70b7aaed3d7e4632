// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>
#include <vector>

#include "freeform_inspection/pipeline.h"

/// @file config_yaml.h
/// Reads a PipelineConfig from YAML shaped like config/default.yaml.

namespace freeform_inspection {

/// Result of reading a configuration file.
struct ConfigLoadResult {
  Status status;          ///< kInvalidInput naming every bad or unknown key
  PipelineConfig config;  ///< defaults overridden by the file's keys
};

/// @brief Starts from the struct defaults and overrides every key present. Unknown keys, values
/// of the wrong type and configurations that do not validate() are errors: a misspelt key
/// silently ignored is a classic source of wrong inspections.
ConfigLoadResult loadPipelineConfigFile(const std::string& path);

/// @brief Same as loadPipelineConfigFile() for YAML text.
ConfigLoadResult parsePipelineConfig(const std::string& yaml_text);

}  // namespace freeform_inspection
