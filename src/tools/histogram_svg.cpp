// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "histogram_svg.h"

#include <algorithm>
#include <cstdio>

#include "freeform_inspection/deviation_colours.h"

namespace freeform_inspection {
namespace {

constexpr double kWidth = 640.0;  // [px] whole drawing
constexpr double kHeight = 240.0;
constexpr double kLeft = 56.0;  // [px] plot area
constexpr double kRight = 624.0;
constexpr double kTop = 16.0;
constexpr double kBottom = 200.0;

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), pattern, value);
  return text;
}

std::string hex(const Rgb& colour) {
  char text[8];
  std::snprintf(text, sizeof(text), "#%02x%02x%02x", colour[0], colour[1], colour[2]);
  return text;
}

// Maps a deviation [m] to the x pixel of the plot.
struct XAxis {
  double low = 0.0;
  double high = 1.0;
  double operator()(double deviation) const {
    return kLeft + (deviation - low) / (high - low) * (kRight - kLeft);
  }
  bool contains(double deviation) const { return deviation >= low && deviation <= high; }
};

std::string bars(const DeviationStatistics& s, const ToleranceConfig& tolerance, const XAxis& x) {
  const std::size_t peak = std::max<std::size_t>(
      1, *std::max_element(s.histogram_counts.begin(), s.histogram_counts.end()));
  std::string svg;
  for (std::size_t i = 0; i < s.histogram_counts.size(); ++i) {
    const double a = s.histogram_edges[i];
    const double b = s.histogram_edges[i + 1];
    // A non-empty bin stays visible next to a tall peak: the tails are what an engineer looks
    // for.
    const double h = s.histogram_counts[i] == 0
                         ? 0.0
                         : std::max(2.0,
                                    (kBottom - kTop) * static_cast<double>(s.histogram_counts[i]) /
                                        static_cast<double>(peak));
    svg += "<rect x=\"" + format("%.1f", x(a)) + "\" y=\"" + format("%.1f", kBottom - h) +
           "\" width=\"" + format("%.1f", std::max(x(b) - x(a) - 1.0, 0.5)) + "\" height=\"" +
           format("%.1f", h) + "\" fill=\"" + hex(deviationColour(0.5 * (a + b), tolerance)) +
           "\"><title>" + format("%+.4f", a * 1e3) + " to " + format("%+.4f", b * 1e3) +
           " mm: " + std::to_string(s.histogram_counts[i]) + " points</title></rect>\n";
  }
  return svg + "<text x=\"" + format("%.0f", kLeft - 4) + "\" y=\"" + format("%.0f", kTop + 4) +
         "\" text-anchor=\"end\">" + std::to_string(peak) + "</text>\n";
}

std::string toleranceLine(double limit, const char* name, const XAxis& x) {
  if (!x.contains(limit)) {
    return "";
  }
  const std::string at = format("%.1f", x(limit));
  return "<line x1=\"" + at + "\" y1=\"" + format("%.0f", kTop) + "\" x2=\"" + at + "\" y2=\"" +
         format("%.0f", kBottom) + "\" stroke=\"#333\" stroke-dasharray=\"4 3\"/>\n<text x=\"" +
         at + "\" y=\"" + format("%.0f", kTop - 4) + "\" text-anchor=\"middle\">" + name +
         "</text>\n";
}

std::string tick(double deviation, const XAxis& x) {
  const std::string at = format("%.1f", x(deviation));
  return "<line x1=\"" + at + "\" y1=\"" + format("%.0f", kBottom) + "\" x2=\"" + at + "\" y2=\"" +
         format("%.0f", kBottom + 4) + "\" stroke=\"#333\"/>\n<text x=\"" + at + "\" y=\"" +
         format("%.0f", kBottom + 16) + "\" text-anchor=\"middle\">" +
         format("%+.3f", deviation * 1e3) + "</text>\n";
}

std::string axes(const XAxis& x, const ToleranceConfig& tolerance) {
  std::string svg = "<line x1=\"" + format("%.0f", kLeft) + "\" y1=\"" + format("%.0f", kBottom) +
                    "\" x2=\"" + format("%.0f", kRight) + "\" y2=\"" + format("%.0f", kBottom) +
                    "\" stroke=\"#333\"/>\n";
  for (const double at : {x.low, 0.0, x.high, tolerance.lower, tolerance.upper}) {
    if (x.contains(at)) {
      svg += tick(at, x);
    }
  }
  return svg + "<text x=\"" + format("%.0f", 0.5 * (kLeft + kRight)) + "\" y=\"" +
         format("%.0f", kHeight - 6) +
         "\" text-anchor=\"middle\">signed deviation [mm] (outer bins hold the tails)</text>\n";
}

}  // namespace

std::string histogramSvg(const DeviationStatistics& statistics, const ToleranceConfig& tolerance) {
  const auto& edges = statistics.histogram_edges;
  if (statistics.histogram_counts.empty() ||
      edges.size() != statistics.histogram_counts.size() + 1 || !(edges.back() > edges.front())) {
    return "<p class=\"none\">No histogram: no deviation was measured.</p>\n";
  }
  const XAxis x{edges.front(), edges.back()};
  return "<svg class=\"histogram\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
         format("%.0f", kWidth) + "\" height=\"" + format("%.0f", kHeight) + "\" viewBox=\"0 0 " +
         format("%.0f", kWidth) + " " + format("%.0f", kHeight) +
         "\" font-family=\"sans-serif\" font-size=\"11\" role=\"img\" "
         "aria-label=\"deviation histogram\">\n" +
         bars(statistics, tolerance, x) + axes(x, tolerance) +
         toleranceLine(tolerance.lower, "lower", x) + toleranceLine(tolerance.upper, "upper", x) +
         "</svg>\n";
}

}  // namespace freeform_inspection
