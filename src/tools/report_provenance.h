// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <ctime>
#include <string>
#include <utility>
#include <vector>

#include "freeform_inspection/pipeline.h"

namespace freeform_inspection {

/// What was inspected, with what, and when: the traceability block of a report.
struct ReportProvenance {
  std::string cad_file;     ///< CAD file as named on the command line
  std::string scan_file;    ///< scan file as named on the command line
  std::string model_id;     ///< Model::id()
  std::string model_key;    ///< Model::descriptorKey(): hash of the mesh and descriptor settings
  std::string scan_hash;    ///< fileHash() of the scan file
  std::string config_hash;  ///< configHash() of the effective configuration
  std::string created;      ///< UTC time of the run, ISO 8601 (utcTimestamp())
  std::string part_id;      ///< the part's serial or id where the caller names one
};

/// @brief XXH3-64 (content_hash.h) of a file's bytes as 16 hex digits; "unreadable" when the file
/// cannot be read.
std::string fileHash(const std::string& path);

/// @brief Every configuration key (config_fields.h) with its value as text, in table order;
/// doubles as the shortest text that reads back to the same value, so the text pins it.
std::vector<std::pair<std::string, std::string>> configEntries(const PipelineConfig& config);

/// @brief XXH3-64 over the "key=value\n" lines of configEntries(): equal for equal settings
/// however they were given (defaults, YAML, flags).
std::string configHash(const PipelineConfig& config);

/// @brief `time` as "YYYY-MM-DDThh:mm:ssZ".
std::string utcTimestamp(std::time_t time);

}  // namespace freeform_inspection
