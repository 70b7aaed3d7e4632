// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "report_provenance.h"

#include "freeform_inspection/pipeline.h"

namespace freeform_inspection {

/// One CSV file of the report: its name and its text.
struct CsvTable {
  std::string file;  ///< e.g. "defects.csv"
  std::string text;  ///< header line, then one line per row, each ending in "\n"
};

/// @brief The inspection as CSV tables for spreadsheets and SPC tools (docs/reports.md, "CSV
/// tables"): summary.csv (one row: traceability, verdict, statistics), defects.csv, histogram.csv
/// and regions.csv. Lengths in millimetres, named with their unit (`peak_mm`); an unknown number
/// is an empty field; RFC 4180 quoting. Every table has its header, also when it has no rows.
std::vector<CsvTable> renderCsvTables(const InspectionResult& result,
                                      const PipelineConfig& config,
                                      const ReportProvenance& provenance);

/// @brief renderCsvTables() written into `directory`, which is created when missing.
/// @return kInvalidInput "cannot write CSV table '<path>': <OS reason>" (or "cannot create CSV
/// directory ...") on the first failure.
Status saveCsvTables(const std::string& directory,
                     const InspectionResult& result,
                     const PipelineConfig& config,
                     const ReportProvenance& provenance);

/// @brief summary.csv's row appended to the file at `path`, its header first when the file is new
/// or empty: one line per inspection, for trends across parts.
/// @return kInvalidInput naming the file when it cannot be written, or when its header is not
/// this version's (an older file: nothing is appended to it).
Status appendCsvSummary(const std::string& path,
                        const InspectionResult& result,
                        const PipelineConfig& config,
                        const ReportProvenance& provenance);

}  // namespace freeform_inspection
