// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstdint>
#include <string>

/// Whole-string number parsing for the command-line tools: "12abc" is an error, not 12.
namespace freeform_inspection::tools {

/// @brief The whole of `text` as a double; false (value unspecified) otherwise.
inline bool parseDouble(const std::string& text, double& value) {
  try {
    std::size_t used = 0;
    value = std::stod(text, &used);
    return used == text.size();
  } catch (...) {
    return false;
  }
}

/// @brief The whole of `text` as decimal digits; false (value unspecified) otherwise.
inline bool parseUnsigned(const std::string& text, std::uint64_t& value) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
    return false;
  }
  try {
    value = std::stoull(text);
    return true;
  } catch (...) {
    return false;
  }
}

}  // namespace freeform_inspection::tools
