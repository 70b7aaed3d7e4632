// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace freeform_inspection {

/// Command line of freeform_inspect (design.md §5). Lengths are metres after scaling.
struct CliOptions {
  std::string cad_path;             ///< --cad
  std::string scan_path;            ///< --scan
  double cad_scale = 1.0;           ///< --cad-scale [m per file unit]
  double scan_scale = 1.0;          ///< --scan-scale [m per file unit]
  std::optional<double> tolerance;  ///< --tolerance [m], symmetric band ±T
  std::string config_path;          ///< --config FILE.yaml
  std::string regions_path;         ///< --regions FILE.yaml (regions.h)
  std::string points_path;          ///< --points FILE.yaml (comparison_points.h)
  std::string report_path;          ///< --report OUT.json
  std::string deviation_path;       ///< --deviation OUT.ply
  std::string html_path;            ///< --html OUT.html
  std::string csv_directory;        ///< --csv DIR (report_csv.h)
  std::string part_id;              ///< --part-id ID: the part's serial, on every report
  std::string model_cache;          ///< --model-cache DIR (empty: the default directory)
  bool no_model_cache = false;      ///< --no-model-cache
  /// --initial-pose: the scan → CAD transform to refine instead of searching, row-major, its
  /// first three rows (12 numbers; a fourth row 0 0 0 1 may follow). Empty: search.
  std::vector<double> initial_pose;
  /// --fixed-pose: the scan → CAD transform to inspect at as it is (no registration), in
  /// --initial-pose's form. Empty: none. At most one of the two is given.
  std::vector<double> fixed_pose;
  bool help = false;  ///< --help
};

/// Parsed command line, or the one-line reason it could not be parsed.
struct CliParseResult {
  std::optional<CliOptions> options;
  std::string error;
};

/// @brief Parses argv (without the program name).
CliParseResult parseCliOptions(const std::vector<std::string>& args);

/// @brief The usage text printed by --help.
std::string cliUsage();

/// @brief Where the model's descriptors and symmetries are cached (model_cache.h): --model-cache,
/// else $XDG_CACHE_HOME/freeform_inspection/models, else $HOME/.cache/freeform_inspection/models;
/// empty (no cache) with --no-model-cache or when neither variable is set.
std::string modelCacheDirectory(const CliOptions& options);

}  // namespace freeform_inspection
