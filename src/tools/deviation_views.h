// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>

#include "splat_renderer.h"

#include "freeform_inspection/deviation.h"

namespace freeform_inspection {

/// @brief The coloured deviation map as HTML figures: one PNG (inline data URI) per view of
/// principalViews(), each captioned with its viewing direction in the CAD frame.
/// @return the figures; a short `<p>` when the map is empty.
std::string deviationViewsHtml(const DeviationMap& map,
                               const ToleranceBands& tolerance,
                               const SplatConfig& config = SplatConfig());

/// @brief The colour legend as an HTML table: swatch, band, range in mm and the share of the
/// map's points in each band. `tolerance`: each point's band (regions.h), the ranges shown the
/// part's.
std::string colourLegendHtml(const DeviationMap& map, const ToleranceBands& tolerance);

}  // namespace freeform_inspection
