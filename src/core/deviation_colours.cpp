// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/deviation_colours.h"

#include <cmath>
#include <cstdlib>
#include <limits>

namespace freeform_inspection {
namespace {

// Index = band + 3. Blue (missing) and red (excess) darken and saturate away from the green
// tolerance band; the light first bands stay distinct from the grey of "no data".
constexpr std::array<Rgb, 2 * kOutOfToleranceBands + 1> kBandColours = {{
    {20, 40, 150},    // -3: missing > 3x tolerance
    {60, 110, 215},   // -2
    {150, 190, 240},  // -1
    {60, 175, 75},    //  0: in tolerance
    {250, 175, 150},  // +1
    {230, 90, 65},    // +2
    {175, 20, 30},    // +3: excess > 3x tolerance
}};

// Width of one out-of-tolerance band on each side: the tolerance on that side. A band that does
// not contain zero (e.g. a machining allowance [+0.1, +0.3] mm) has no tolerance on one side;
// its width stands in there.
double excessStep(const ToleranceConfig& tolerance) {
  return tolerance.upper > 0.0 ? tolerance.upper : tolerance.upper - tolerance.lower;
}

double missingStep(const ToleranceConfig& tolerance) {
  return tolerance.lower < 0.0 ? -tolerance.lower : tolerance.upper - tolerance.lower;
}

// Edge k (0..3) of the excess side: upper + k·step; of the missing side: lower - k·step.
double excessEdge(const ToleranceConfig& tolerance, int k) {
  return tolerance.upper + k * excessStep(tolerance);
}

double missingEdge(const ToleranceConfig& tolerance, int k) {
  return tolerance.lower - k * missingStep(tolerance);
}

std::string bandLabel(int band) {
  if (band == 0) {
    return "in tolerance";
  }
  const std::string side = band > 0 ? "excess " : "missing ";
  const int steps = std::abs(band);
  if (steps == kOutOfToleranceBands) {
    return side + ">" + std::to_string(steps) + "x tolerance";
  }
  return side + std::to_string(steps) + "-" + std::to_string(steps + 1) + "x tolerance";
}

}  // namespace

int deviationBand(double deviation, const ToleranceConfig& tolerance) {
  if (std::isnan(deviation)) {
    return kNoDataBand;
  }
  for (int k = 0; k < kOutOfToleranceBands; ++k) {
    if (deviation > tolerance.upper && deviation <= excessEdge(tolerance, k + 1)) {
      return k + 1;
    }
    if (deviation < tolerance.lower && deviation >= missingEdge(tolerance, k + 1)) {
      return -(k + 1);
    }
  }
  if (deviation > tolerance.upper) {
    return kOutOfToleranceBands;
  }
  if (deviation < tolerance.lower) {
    return -kOutOfToleranceBands;
  }
  return 0;
}

Rgb bandColour(int band) {
  if (band < -kOutOfToleranceBands || band > kOutOfToleranceBands) {
    return kNoDataColour;
  }
  const int index = band + kOutOfToleranceBands;
  return kBandColours[static_cast<std::size_t>(index)];
}

Rgb deviationColour(double deviation, const ToleranceConfig& tolerance) {
  return bandColour(deviationBand(deviation, tolerance));
}

bool inTolerance(double deviation, const ToleranceConfig& tolerance) {
  return deviation >= tolerance.lower && deviation <= tolerance.upper;
}

std::vector<ColourBand> deviationLegend(const ToleranceConfig& tolerance) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<ColourBand> legend;
  for (int band = -kOutOfToleranceBands; band <= kOutOfToleranceBands; ++band) {
    ColourBand entry;
    entry.band = band;
    entry.colour = bandColour(band);
    entry.label = bandLabel(band);
    if (band < 0) {
      entry.low = band == -kOutOfToleranceBands ? -kInf : missingEdge(tolerance, -band);
      entry.high = missingEdge(tolerance, -band - 1);
    } else if (band > 0) {
      entry.low = excessEdge(tolerance, band - 1);
      entry.high = band == kOutOfToleranceBands ? kInf : excessEdge(tolerance, band);
    } else {
      entry.low = tolerance.lower;
      entry.high = tolerance.upper;
    }
    legend.push_back(entry);
  }
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  legend.push_back({kNoDataBand, kNaN, kNaN, kNoDataColour, "no CAD near"});
  return legend;
}

}  // namespace freeform_inspection
