// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "freeform_inspection/deviation.h"

/// @file deviation_colours.h
/// The banded colour scale of the signed deviation, shared by the CLI's PLY and HTML outputs and
/// the node's rviz cloud. Bands, not a continuous ramp: an engineer reads "between one and two
/// tolerances" off a band at a glance, a shade of a ramp needs the legend every time.
///
/// Band 0 is the tolerance band [lower, upper] (green). Excess material (deviation > upper) goes
/// through bands +1, +2, +3 of increasingly saturated red, missing material (< lower) through
/// -1, -2, -3 of increasingly saturated blue. Band edges sit at whole multiples of the tolerance
/// on each side: upper, 2·upper, 3·upper and lower, 2·lower, 3·lower for the usual band with
/// lower < 0 < upper. Each side uses its own tolerance, so asymmetric bands keep their meaning.
/// A value exactly on an edge belongs to the band nearer zero. NaN (no CAD surface near the
/// point) is grey.

namespace freeform_inspection {

/// An 8-bit sRGB colour: red, green, blue.
using Rgb = std::array<std::uint8_t, 3>;

/// Number of bands on each side of the tolerance band.
constexpr int kOutOfToleranceBands = 3;

/// Band index of "no CAD near the point" (NaN deviation).
constexpr int kNoDataBand = 100;

/// Colour of points without a deviation (unmatched): neutral grey.
constexpr Rgb kNoDataColour = {160, 160, 160};

/// One band of the colour scale, for legends.
struct ColourBand {
  int band = 0;  ///< -3..3 (0 = in tolerance), or kNoDataBand
  /// [m] lower end: exclusive for excess bands, inclusive otherwise; -inf for band -3, NaN for
  /// no data
  double low = 0.0;
  /// [m] upper end: exclusive for missing-material bands, inclusive otherwise; +inf for band +3,
  /// NaN for no data
  double high = 0.0;
  Rgb colour = kNoDataColour;  ///< its colour
  std::string label;           ///< e.g. "in tolerance", "excess 1-2x tolerance", "no CAD near"
};

/// @brief Band of a signed deviation [m] against the tolerance band.
/// @return -3..3 (0 inside [lower, upper]), kNoDataBand for NaN.
int deviationBand(double deviation, const ToleranceConfig& tolerance);

/// @brief Colour of a band index as returned by deviationBand().
Rgb bandColour(int band);

/// @brief Colour of a signed deviation [m]: deviationBand() then bandColour().
Rgb deviationColour(double deviation, const ToleranceConfig& tolerance);

/// @brief True when the deviation lies inside [lower, upper] (NaN is not).
bool inTolerance(double deviation, const ToleranceConfig& tolerance);

/// @brief Every band with its range in metres for this tolerance, from the most missing
/// material (-3) to the most excess (+3), then the no-data band.
std::vector<ColourBand> deviationLegend(const ToleranceConfig& tolerance);

}  // namespace freeform_inspection
