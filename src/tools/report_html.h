// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>

#include "report_provenance.h"

#include "freeform_inspection/pipeline.h"

namespace freeform_inspection {

/// @brief The self-contained HTML inspection report (docs/reports.md): verdict banner,
/// traceability, registration, tolerance, statistics, histogram (inline SVG), pictures of the
/// coloured deviation map (inline PNG) with the legend, defects, warnings and the effective
/// configuration. No scripts, no external resources: it opens offline and archives as one file.
std::string renderHtmlReport(const InspectionResult& result,
                             const PipelineConfig& config,
                             const ReportProvenance& provenance);

/// @brief renderHtmlReport() written to `path`.
/// @return kInvalidInput "cannot write HTML report '<path>': <OS reason>" on I/O failure.
Status saveHtmlReport(const std::string& path,
                      const InspectionResult& result,
                      const PipelineConfig& config,
                      const ReportProvenance& provenance);

}  // namespace freeform_inspection
