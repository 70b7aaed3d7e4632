// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "deviation_views.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "base64.h"
#include "html_util.h"
#include "png_writer.h"

#include "freeform_inspection/deviation_colours.h"

namespace freeform_inspection {
namespace {

std::string swatch(const Rgb& colour) {
  char style[64];
  std::snprintf(style, sizeof(style), "background:#%02x%02x%02x", colour[0], colour[1], colour[2]);
  return std::string("<span class=\"swatch\" style=\"") + style + "\"></span>";
}

// "-0.2000 to +0.2000 mm"; open ends as "below"/"above", no data as "-".
std::string rangeText(const ColourBand& band) {
  if (std::isnan(band.low)) {
    return "-";
  }
  if (std::isinf(band.low)) {
    return "below " + millimetres(band.high);
  }
  if (std::isinf(band.high)) {
    return "above " + millimetres(band.low);
  }
  return number(band.low * 1e3, 4) + " to " + millimetres(band.high);
}

std::string directionText(const Eigen::Vector3d& toward_viewer) {
  const Eigen::Vector3d d = -toward_viewer;  // the direction the camera looks in
  return "looking along (" + number(d.x(), 2) + ", " + number(d.y(), 2) + ", " + number(d.z(), 2) +
         ") in the CAD frame";
}

}  // namespace

std::string deviationViewsHtml(const DeviationMap& map,
                               const ToleranceBands& tolerance,
                               const SplatConfig& config) {
  if (map.size() == 0 || map.deviation.size() != map.size()) {
    return "<p class=\"none\">No deviation map: the scan was not evaluated.</p>\n";
  }
  std::vector<Rgb> colours;
  colours.reserve(map.size());
  for (std::size_t i = 0; i < map.size(); ++i) {
    colours.push_back(deviationColour(map.deviation[i], tolerance.at(i)));
  }
  std::string html = "<div class=\"views\">\n";
  for (const OrthoView& view : principalViews(map.points)) {
    const std::string png = encodePng(renderSplats(map.points, colours, view, config));
    html += "<figure><img alt=\"deviation map, " + view.name + " view\" width=\"" +
            std::to_string(config.width) + "\" height=\"" + std::to_string(config.height) +
            "\" src=\"" + dataUri("image/png", png) + "\"><figcaption>" + view.name + ", " +
            directionText(view.axes.row(2).transpose()) + "</figcaption></figure>\n";
  }
  return html + "</div>\n";
}

std::string colourLegendHtml(const DeviationMap& map, const ToleranceBands& tolerance) {
  std::map<int, std::size_t> counts;
  for (std::size_t i = 0; i < map.deviation.size(); ++i) {
    ++counts[deviationBand(map.deviation[i], tolerance.at(i))];
  }
  const double total = static_cast<double>(std::max<std::size_t>(map.deviation.size(), 1));
  std::string html =
      "<table class=\"legend\">\n<tr><th></th><th>band</th><th>signed deviation</th>"
      "<th>points</th></tr>\n";
  for (const ColourBand& band : deviationLegend(tolerance.part)) {
    const std::size_t count = counts[band.band];
    html += "<tr><td>" + swatch(band.colour) + "</td><td>" + escapeHtml(band.label) + "</td><td>" +
            rangeText(band) + "</td><td>" + std::to_string(count) + " (" +
            percent(static_cast<double>(count) / total) + ")</td></tr>\n";
  }
  html += "</table>\n";
  if (!tolerance.region_bands.empty()) {
    html +=
        "<p>Named regions are coloured against their own band: the ranges above are the "
        "part's.</p>\n";
  }
  return html;
}

}  // namespace freeform_inspection
