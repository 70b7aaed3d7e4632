// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// freeform_inspect: the offline inspection job on files, the same pipeline as the node.
#include <chrono>
#include <ctime>
#include <exception>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "cli_options.h"
#include "deviation_ply.h"
#include "report_csv.h"
#include "report_html.h"
#include "report_json.h"
#include "report_provenance.h"

#include "freeform_inspection/comparison_points.h"
#include "freeform_inspection/config_yaml.h"
#include "freeform_inspection/io.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/pipeline.h"
#include "freeform_inspection/process_memory.h"
#include "freeform_inspection/regions.h"

namespace fi = freeform_inspection;

namespace {

constexpr int kExitRan = 0;
constexpr int kExitBadInput = 2;

// The one line on stderr for a refusal.
int refuse(const std::string& reason) {
  std::cerr << "freeform_inspect: " << reason << "\n";
  return kExitBadInput;
}

bool isInputProblem(fi::StatusCode code) {
  return code == fi::StatusCode::kInvalidInput || code == fi::StatusCode::kDegenerateInput ||
         code == fi::StatusCode::kUnitsMismatch;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Reads the YAML configuration (or the defaults), the regions and the comparison points, and
// applies --tolerance.
fi::ConfigLoadResult configure(const fi::CliOptions& options) {
  fi::ConfigLoadResult loaded;
  if (!options.config_path.empty()) {
    loaded = fi::loadPipelineConfigFile(options.config_path);
  }
  if (loaded.status.ok() && !options.regions_path.empty()) {
    fi::RegionsLoadResult regions = fi::loadRegionsFile(options.regions_path);
    loaded.status = regions.status;
    loaded.config.regions = std::move(regions.regions);
  }
  if (loaded.status.ok() && !options.points_path.empty()) {
    fi::ComparisonPointsLoadResult points = fi::loadComparisonPointsFile(options.points_path);
    loaded.status = points.status;
    loaded.config.comparison_points = std::move(points.points);
    loaded.config.datum_precedence = std::move(points.datum_precedence);
  }
  if (options.tolerance) {
    loaded.config.tolerance.upper = *options.tolerance;
    loaded.config.tolerance.lower = -*options.tolerance;
  }
  return loaded;
}

// Prints the report and writes the requested files; returns false if a write failed.
bool emit(const fi::CliOptions& options, const nlohmann::ordered_json& report) {
  std::cout << report.dump(2) << std::endl;
  if (options.report_path.empty()) {
    return true;
  }
  std::ofstream file(options.report_path);
  file << report.dump(2) << "\n";
  return static_cast<bool>(file);
}

// The deviation PLY needs a deviation map, which only a registered scan has; the JSON says
// why the file is missing instead of leaving an empty PLY behind.
void noteSkippedOutputs(const fi::CliOptions& options, fi::InspectionResult* result) {
  if (!options.deviation_path.empty() && result->deviation_map.size() == 0) {
    result->warnings.push_back("deviation file '" + options.deviation_path +
                               "' not written: no deviation map (the scan was not registered)");
  }
}

fi::ReportProvenance provenance(const fi::CliOptions& options,
                                const fi::Model& model,
                                std::time_t started) {
  fi::ReportProvenance p;
  p.cad_file = options.cad_path;
  p.scan_file = options.scan_path;
  p.model_id = model.id();
  p.model_key = model.descriptorKey();
  p.scan_hash = fi::fileHash(options.scan_path);
  p.created = fi::utcTimestamp(started);
  p.part_id = options.part_id;
  return p;
}

// Writes --deviation (when there is a map), --html and --csv (always: a failed inspection is on
// record too); returns the first failure.
fi::Status writeOutputs(const fi::CliOptions& options,
                        const fi::InspectionResult& result,
                        const fi::PipelineConfig& config,
                        const fi::Model& model,
                        std::time_t started) {
  if (!options.deviation_path.empty() && result.deviation_map.size() > 0) {
    fi::Status written = fi::saveDeviationPly(
        options.deviation_path,
        result.deviation_map,
        result.scan_faces,
        fi::toleranceBands(config.regions, result.deviation_map.region, config.tolerance));
    if (!written.ok()) {
      return written;
    }
  }
  if (options.html_path.empty() && options.csv_directory.empty()) {
    return fi::Status::success();
  }
  const fi::ReportProvenance record = provenance(options, model, started);
  if (!options.html_path.empty()) {
    const fi::Status written = fi::saveHtmlReport(options.html_path, result, config, record);
    if (!written.ok()) {
      return written;
    }
  }
  if (!options.csv_directory.empty()) {
    return fi::saveCsvTables(options.csv_directory, result, config, record);
  }
  return fi::Status::success();
}

// --initial-pose's or --fixed-pose's 12 numbers as a transform (the core checks that it is
// rigid).
Eigen::Isometry3d toPose(const std::vector<double>& numbers) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col) {
      pose.matrix()(row, col) = numbers[static_cast<std::size_t>(4 * row + col)];
    }
  }
  return pose;
}

fi::InspectionResult inspectScan(const fi::CliOptions& options,
                                 const fi::Model& model,
                                 const fi::Scan& scan,
                                 const fi::PipelineConfig& config) {
  if (!options.fixed_pose.empty()) {
    return fi::inspectAt(model, scan, toPose(options.fixed_pose), config);
  }
  if (!options.initial_pose.empty()) {
    return fi::inspectFrom(model, scan, toPose(options.initial_pose), config);
  }
  return fi::inspect(model, scan, config);
}

int run(const fi::CliOptions& options) {
  const std::time_t started = std::time(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const fi::ConfigLoadResult config = configure(options);
  if (!config.status.ok()) {
    return refuse(config.status.message);
  }
  const fi::ModelLoadResult model = fi::loadModel(options.cad_path,
                                                  options.cad_scale,
                                                  "cad",
                                                  config.config.descriptor,
                                                  fi::modelCacheDirectory(options));
  if (!model.status.ok()) {
    return refuse(model.status.message);
  }
  const fi::ScanLoadResult scan = fi::loadScan(options.scan_path, options.scan_scale);
  if (!scan.status.ok()) {
    return refuse(scan.status.message);
  }
  const double load_seconds = secondsSince(start);
  fi::InspectionResult result = inspectScan(options, *model.model, scan.scan, config.config);
  result.counts.non_finite += scan.non_finite_removed;
  result.warnings.insert(result.warnings.begin(), model.warnings.begin(), model.warnings.end());
  result.warnings.insert(result.warnings.end(), scan.warnings.begin(), scan.warnings.end());
  noteSkippedOutputs(options, &result);
  result.timings.insert(result.timings.begin(), {"load", load_seconds});
  result.timings.back().seconds = secondsSince(start);  // "total" covers loading too
  nlohmann::ordered_json report = fi::toJson(result);
  report["part_id"] = options.part_id;
  if (!emit(options, report)) {
    return refuse("cannot write report '" + options.report_path + "'");
  }
  const fi::Status written = writeOutputs(options, result, config.config, *model.model, started);
  if (!written.ok()) {
    return refuse(written.message);
  }
  if (isInputProblem(result.status.code)) {
    return refuse(result.status.message);
  }
  return kExitRan;
}

}  // namespace

int main(int argc, char** argv) {
  fi::tuneProcessMemory();
  const fi::CliParseResult parsed =
      fi::parseCliOptions(std::vector<std::string>(argv + 1, argv + argc));
  if (!parsed.options) {
    return refuse(parsed.error);
  }
  if (parsed.options->help) {
    std::cout << fi::cliUsage();
    return kExitRan;
  }
  try {
    return run(*parsed.options);
  } catch (const std::exception& e) {
    return refuse(std::string("internal error: ") + e.what());
  }
}
