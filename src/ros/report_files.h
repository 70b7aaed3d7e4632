// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>
#include <vector>

#include <std_msgs/Header.h>

#include "freeform_inspection/model.h"
#include "freeform_inspection/pipeline.h"

/// The node's archive of inspection reports (`~report_dir`): the files a quality engineer keeps
/// per part, written by the same code as the CLI's --html and --deviation.
namespace freeform_inspection_ros {

/// What one inspection's files record about where the scan came from.
struct ReportSource {
  std::string model_path;  ///< CAD file the model was loaded from
  std::string scan_name;   ///< e.g. "Inspect request" or "topic /scan"
  std::string scan_hash;   ///< XXH3-64 of the scan message's point data
  std::string part_id;     ///< from the request; may be empty
};

/// Files written, or the reason one could not be.
struct ReportFilesResult {
  std::vector<std::string> files;  ///< absolute paths, HTML first, inspections.csv last
  std::string error;               ///< "" when every file was written
};

/// @brief The base name of one inspection's files: the part id reduced to [A-Za-z0-9._-] (so a
/// request cannot name a path outside the directory), then the scan's stamp, e.g.
/// "SN-42_1234.500000000"; "inspection_<stamp>" without a part id.
std::string reportBaseName(const std::string& part_id, const std_msgs::Header& header);

/// The file in `~report_dir` that gets one line per inspection (report_csv.h's summary row).
inline constexpr char kInspectionLog[] = "inspections.csv";

/// @brief Writes `<dir>/<base>.html` and, when the scan was registered, `<base>_deviation.ply`,
/// then appends the inspection's line to `<dir>/inspections.csv` (kInspectionLog). The directory
/// is created if missing.
ReportFilesResult writeReportFiles(const std::string& dir,
                                   const freeform_inspection::InspectionResult& result,
                                   const freeform_inspection::PipelineConfig& config,
                                   const freeform_inspection::Model& model,
                                   const ReportSource& source,
                                   const std_msgs::Header& header);

}  // namespace freeform_inspection_ros
