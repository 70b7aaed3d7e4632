// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>
#include <string_view>
#include <vector>

/// Small helpers for writing the HTML report by hand (no template engine needed for one page).

namespace freeform_inspection {

/// @brief `text` with & < > " ' escaped, safe inside elements and quoted attributes.
std::string escapeHtml(std::string_view text);

/// @brief A length [m] in millimetres with `decimals` digits ("0.0217 mm"); "n/a" for NaN/inf.
std::string millimetres(double metres, int decimals = 4);

/// @brief A share as a percentage ("93.1 %"); "n/a" for NaN/inf.
std::string percent(double share);

/// @brief A plain number with `decimals` digits; "n/a" for NaN/inf.
std::string number(double value, int decimals);

/// @brief One table row: a header cell then data cells (already HTML, not escaped again).
std::string tableRow(const std::string& header, const std::vector<std::string>& cells);

}  // namespace freeform_inspection
