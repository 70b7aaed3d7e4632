// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <string>
#include <variant>
#include <vector>

#include "freeform_inspection/pipeline.h"

/// @file config_fields.h
/// One table of every tunable PipelineConfig field with its key ("input/max_points"). The YAML
/// reader (CLI) and the ROS parameter reader (node) both walk this table, so a key cannot exist
/// in one place and be missing in the other, and unknown keys can be refused.

namespace freeform_inspection {

/// A named, writable field of a PipelineConfig.
struct ConfigField {
  std::string key;  ///< "<section>/<name>", as nested in config/default.yaml
  /// where the value goes (a list of numbers for std::vector<double>)
  std::variant<double*, std::size_t*, int*, bool*, std::vector<double>*> target;
};

/// @brief The fields of `config`, pointing into it. The pointers live as long as `config`.
std::vector<ConfigField> configFields(PipelineConfig& config);

}  // namespace freeform_inspection
