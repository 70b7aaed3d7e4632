// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "report_files.h"

#include <cctype>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <system_error>

#include "deviation_ply.h"
#include "report_csv.h"
#include "report_html.h"
#include "report_provenance.h"

namespace freeform_inspection_ros {

namespace fi = freeform_inspection;

std::string reportBaseName(const std::string& part_id, const std_msgs::Header& header) {
  std::string base;
  for (const char c : part_id) {
    const bool safe = std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_' ||
                      (c == '.' && !base.empty());  // no leading dot: no "..", no hidden file
    base += safe ? c : '_';
  }
  if (base.empty()) {
    base = "inspection";
  }
  char stamp[32];
  std::snprintf(stamp, sizeof(stamp), "_%u.%09u", header.stamp.sec, header.stamp.nsec);
  return base + stamp;
}

ReportFilesResult writeReportFiles(const std::string& dir,
                                   const fi::InspectionResult& result,
                                   const fi::PipelineConfig& config,
                                   const fi::Model& model,
                                   const ReportSource& source,
                                   const std_msgs::Header& header) {
  ReportFilesResult written;
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) {
    written.error = "cannot create ~report_dir '" + dir + "': " + error.message();
    return written;
  }
  const std::filesystem::path base =
      std::filesystem::absolute(dir) / reportBaseName(source.part_id, header);
  fi::ReportProvenance provenance;
  provenance.cad_file = source.model_path;
  provenance.scan_file = source.scan_name + " (" + header.frame_id + ", stamp " +
                         std::to_string(header.stamp.toSec()) + ")";
  provenance.model_id = model.id();
  provenance.model_key = model.descriptorKey();
  provenance.scan_hash = source.scan_hash;
  provenance.created = fi::utcTimestamp(std::time(nullptr));
  provenance.part_id = source.part_id;
  const std::string html = base.string() + ".html";
  fi::Status status = fi::saveHtmlReport(html, result, config, provenance);
  if (!status.ok()) {
    written.error = status.message;
    return written;
  }
  written.files.push_back(html);
  if (result.deviation_map.size() > 0) {
    const std::string ply = base.string() + "_deviation.ply";
    status = fi::saveDeviationPly(
        ply,
        result.deviation_map,
        result.scan_faces,
        fi::toleranceBands(config.regions, result.deviation_map.region, config.tolerance));
    if (!status.ok()) {
      written.error = status.message;
      return written;
    }
    written.files.push_back(ply);
  }
  const std::string log = (std::filesystem::absolute(dir) / kInspectionLog).string();
  status = fi::appendCsvSummary(log, result, config, provenance);
  if (!status.ok()) {
    written.error = status.message;
    return written;
  }
  written.files.push_back(log);
  return written;
}

}  // namespace freeform_inspection_ros
