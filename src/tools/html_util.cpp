// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "html_util.h"

#include <cmath>
#include <cstdio>

namespace freeform_inspection {

std::string escapeHtml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out.push_back(c);
    }
  }
  return out;
}

std::string number(double value, int decimals) {
  if (!std::isfinite(value)) {
    return "n/a";
  }
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

std::string millimetres(double metres, int decimals) {
  return std::isfinite(metres) ? number(metres * 1e3, decimals) + " mm" : "n/a";
}

std::string percent(double share) {
  return std::isfinite(share) ? number(share * 100.0, 1) + " %" : "n/a";
}

std::string tableRow(const std::string& header, const std::vector<std::string>& cells) {
  std::string row = "<tr><th>" + header + "</th>";
  for (const std::string& cell : cells) {
    row += "<td>" + cell + "</td>";
  }
  return row + "</tr>\n";
}

}  // namespace freeform_inspection
