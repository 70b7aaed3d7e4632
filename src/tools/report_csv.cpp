// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "report_csv.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "file_output.h"
#include "html_util.h"

namespace freeform_inspection {
namespace {

// RFC 4180: a field holding a comma, a quote or a line break is quoted, its quotes doubled.
std::string field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) {
    return text;
  }
  std::string quoted = "\"";
  for (const char c : text) {
    quoted += c == '"' ? "\"\"" : std::string(1, c);
  }
  return quoted + "\"";
}

// A number with `decimals` digits after the point (html_util.h's number(): '.', whatever the
// locale), empty when it is unknown.
std::string fixed(double value, int decimals) {
  return std::isfinite(value) ? number(value, decimals) : "";
}

// Lengths [m] in millimetres to 0.1 µm, areas [m²] in mm², shares to 1e-6.
std::string mm(double metres) {
  return fixed(metres * 1e3, 4);
}

std::string mm2(double square_metres) {
  return fixed(square_metres * 1e6, 4);
}

std::string share(double value) {
  return fixed(value, 6);
}

std::string line(const std::vector<std::string>& fields) {
  std::string text;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    text += (i > 0 ? "," : "") + fields[i];
  }
  return text + "\n";
}

// The statistics' columns: names, then the values (empty where nothing was measured).
const std::vector<std::string> kStatisticsHeader = {"points_evaluated",
                                                    "points_unmatched",
                                                    "points_excluded",
                                                    "mean_mm",
                                                    "std_mm",
                                                    "rms_mm",
                                                    "min_mm",
                                                    "max_mm",
                                                    "p5_mm",
                                                    "p50_mm",
                                                    "p95_mm",
                                                    "in_tolerance_fraction",
                                                    "coverage"};

std::vector<std::string> statistics(const DeviationStatistics& s) {
  std::vector<std::string> values = {
      std::to_string(s.evaluated), std::to_string(s.unmatched), std::to_string(s.excluded)};
  const bool measured = s.evaluated > 0;
  for (const double length : {s.mean, s.std, s.rms, s.min, s.max, s.p5, s.p50, s.p95}) {
    values.push_back(measured ? mm(length) : "");
  }
  values.push_back(measured ? share(s.in_tolerance_fraction) : "");
  values.push_back(measured ? share(s.coverage) : "");
  return values;
}

std::vector<std::string> joined(std::vector<std::string> first,
                                const std::vector<std::string>& rest) {
  first.insert(first.end(), rest.begin(), rest.end());
  return first;
}

std::vector<std::string> summaryHeader() {
  return joined(joined({"created",
                        "part_id",
                        "cad_file",
                        "scan_file",
                        "scan_hash",
                        "model_id",
                        "config_hash",
                        "status",
                        "verdict",
                        "verdict_reason",
                        "rmse_mm",
                        "fitness",
                        "lower_mm",
                        "upper_mm"},
                       kStatisticsHeader),
                {"defects"});
}

std::vector<std::string> summaryRow(const InspectionResult& result,
                                    const PipelineConfig& config,
                                    const ReportProvenance& provenance) {
  return joined(joined({field(provenance.created),
                        field(provenance.part_id),
                        field(provenance.cad_file),
                        field(provenance.scan_file),
                        field(provenance.scan_hash),
                        field(provenance.model_id),
                        configHash(config),
                        toString(result.registration),
                        toString(result.verdict),
                        field(result.verdict_reason),
                        mm(result.rmse),
                        share(result.fitness),
                        mm(config.tolerance.lower),
                        mm(config.tolerance.upper)},
                       statistics(result.deviation)),
                {std::to_string(result.defects.size())});
}

std::string defectsTable(const InspectionResult& result) {
  std::string text = line({"id",
                           "region",
                           "kind",
                           "points",
                           "area_mm2",
                           "peak_mm",
                           "mean_mm",
                           "centroid_x_mm",
                           "centroid_y_mm",
                           "centroid_z_mm",
                           "bbox_min_x_mm",
                           "bbox_min_y_mm",
                           "bbox_min_z_mm",
                           "bbox_max_x_mm",
                           "bbox_max_y_mm",
                           "bbox_max_z_mm",
                           "cad_chord_error_mm"});
  for (std::size_t i = 0; i < result.defects.size(); ++i) {
    const DefectRegion& d = result.defects[i];
    std::vector<std::string> row = {std::to_string(i),
                                    field(result.regionName(d.region)),
                                    d.sign > 0 ? "excess" : "missing",
                                    std::to_string(d.points),
                                    mm2(d.area),
                                    mm(d.peak),
                                    mm(d.mean)};
    for (const Eigen::Vector3d* point : {&d.centroid, &d.bbox_min, &d.bbox_max}) {
      for (int axis = 0; axis < 3; ++axis) {
        row.push_back(mm((*point)[axis]));
      }
    }
    row.push_back(mm(d.cad_chord_error));
    text += line(row);
  }
  return text;
}

// One row per bin; the outer bins take the tails, as in the JSON.
std::string histogramTable(const DeviationStatistics& s) {
  std::string text = line({"from_mm", "to_mm", "points"});
  for (std::size_t b = 0; b < s.histogram_counts.size() && b + 1 < s.histogram_edges.size(); ++b) {
    text += line({mm(s.histogram_edges[b]),
                  mm(s.histogram_edges[b + 1]),
                  std::to_string(s.histogram_counts[b])});
  }
  return text;
}

std::string regionsTable(const InspectionResult& result) {
  std::string text = line(
      joined(joined({"name", "evaluated", "verdict", "lower_mm", "upper_mm"}, kStatisticsHeader),
             {"defects", "verdict_reason"}));
  for (const RegionResult& r : result.regions) {
    text += line(joined(joined({field(r.name),
                                r.evaluated ? "true" : "false",
                                toString(r.verdict),
                                mm(r.tolerance.lower),
                                mm(r.tolerance.upper)},
                               statistics(r.deviation)),
                        {std::to_string(r.defects), field(r.verdict_reason)}));
  }
  return text;
}

std::string pointsTable(const InspectionResult& result) {
  std::string text = line({"name",
                           "verdict",
                           "deviation_mm",
                           "lower_mm",
                           "upper_mm",
                           "points",
                           "spread_mm",
                           "nominal_x_mm",
                           "nominal_y_mm",
                           "nominal_z_mm",
                           "off_surface_mm",
                           "radius_mm",
                           "verdict_reason",
                           "datum"});
  for (const ComparisonPointResult& p : result.comparison_points) {
    const bool placed = p.normal.squaredNorm() > 0.0;  // not placed: no position to give
    text += line({field(p.name),
                  toString(p.verdict),
                  mm(p.deviation),
                  mm(p.tolerance.lower),
                  mm(p.tolerance.upper),
                  std::to_string(p.points),
                  mm(p.spread),
                  placed ? mm(p.nominal.x()) : "",
                  placed ? mm(p.nominal.y()) : "",
                  placed ? mm(p.nominal.z()) : "",
                  placed ? mm(p.off_surface) : "",
                  placed ? mm(p.radius) : "",
                  field(p.verdict_reason),
                  field(p.datum)});
  }
  return text;
}

}  // namespace

std::vector<CsvTable> renderCsvTables(const InspectionResult& result,
                                      const PipelineConfig& config,
                                      const ReportProvenance& provenance) {
  return {{"summary.csv", line(summaryHeader()) + line(summaryRow(result, config, provenance))},
          {"defects.csv", defectsTable(result)},
          {"histogram.csv", histogramTable(result.deviation)},
          {"regions.csv", regionsTable(result)},
          {"points.csv", pointsTable(result)}};
}

Status saveCsvTables(const std::string& directory,
                     const InspectionResult& result,
                     const PipelineConfig& config,
                     const ReportProvenance& provenance) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    return Status::failure(StatusCode::kInvalidInput,
                           "cannot create CSV directory '" + directory + "': " + error.message());
  }
  for (const CsvTable& table : renderCsvTables(result, config, provenance)) {
    const Status written = writeOutputFile(
        (std::filesystem::path(directory) / table.file).string(), table.text, "CSV table");
    if (!written.ok()) {
      return written;
    }
  }
  return Status::success();
}

Status appendCsvSummary(const std::string& path,
                        const InspectionResult& result,
                        const PipelineConfig& config,
                        const ReportProvenance& provenance) {
  const std::string header = line(summaryHeader());
  std::string first_line;
  {
    std::ifstream existing(path);
    std::getline(existing, first_line);
  }
  if (!first_line.empty() && first_line + "\n" != header) {
    return Status::failure(StatusCode::kInvalidInput,
                           "cannot append to CSV summary '" + path +
                               "': its header is not this version's (move the file aside)");
  }
  std::ofstream file(path, std::ios::app);
  file << (first_line.empty() ? header : "") << line(summaryRow(result, config, provenance));
  file.close();
  if (!file) {
    return Status::failure(StatusCode::kInvalidInput,
                           "cannot append to CSV summary '" + path + "': " + std::strerror(errno));
  }
  return Status::success();
}

}  // namespace freeform_inspection
