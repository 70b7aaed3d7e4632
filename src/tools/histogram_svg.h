// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>

#include "freeform_inspection/deviation.h"

namespace freeform_inspection {

/// @brief The deviation histogram as an inline SVG element: one bar per bin in the colour of the
/// band its centre falls in, dashed lines at the tolerance limits, axes labelled in mm, a tooltip
/// (range and count) per bar.
/// @return an `<svg>` element; a short `<p>` when the statistics have no histogram.
std::string histogramSvg(const DeviationStatistics& statistics, const ToleranceConfig& tolerance);

}  // namespace freeform_inspection
