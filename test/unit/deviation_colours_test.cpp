// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// The banded deviation colour scale: band edges at whole multiples of the tolerance on each side,
// symmetric for a symmetric band, each side on its own tolerance for an asymmetric one.
#include "freeform_inspection/deviation_colours.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace fi = freeform_inspection;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

fi::ToleranceConfig band(double lower, double upper) {
  fi::ToleranceConfig tolerance;
  tolerance.lower = lower;
  tolerance.upper = upper;
  return tolerance;
}

double above(double value) {
  return std::nextafter(value, kInf);
}
double below(double value) {
  return std::nextafter(value, -kInf);
}

TEST(DeviationColours, SymmetricBandEdgesSitAtWholeMultiplesOfTheTolerance) {
  const fi::ToleranceConfig tolerance = band(-0.0002, 0.0002);
  EXPECT_EQ(fi::deviationBand(0.0, tolerance), 0);
  EXPECT_EQ(fi::deviationBand(0.0002, tolerance), 0) << "the limit itself is in tolerance";
  EXPECT_EQ(fi::deviationBand(above(0.0002), tolerance), 1);
  EXPECT_EQ(fi::deviationBand(0.0004, tolerance), 1);
  EXPECT_EQ(fi::deviationBand(above(0.0004), tolerance), 2);
  EXPECT_EQ(fi::deviationBand(3 * 0.0002, tolerance), 2);
  EXPECT_EQ(fi::deviationBand(above(3 * 0.0002), tolerance), 3);
  EXPECT_EQ(fi::deviationBand(1.0, tolerance), 3);
  EXPECT_EQ(fi::deviationBand(kInf, tolerance), 3);
  EXPECT_EQ(fi::deviationBand(-0.0002, tolerance), 0);
  EXPECT_EQ(fi::deviationBand(below(-0.0002), tolerance), -1);
  EXPECT_EQ(fi::deviationBand(-0.0004, tolerance), -1);
  EXPECT_EQ(fi::deviationBand(below(-0.0004), tolerance), -2);
  EXPECT_EQ(fi::deviationBand(below(-3 * 0.0002), tolerance), -3);
  EXPECT_EQ(fi::deviationBand(-kInf, tolerance), -3);
}

TEST(DeviationColours, SymmetricBandGivesMirroredBands) {
  const fi::ToleranceConfig tolerance = band(-0.0001, 0.0001);
  for (double d = 0.0; d < 0.0006; d += 0.0000137) {
    EXPECT_EQ(fi::deviationBand(-d, tolerance), -fi::deviationBand(d, tolerance)) << d;
  }
}

TEST(DeviationColours, ColoursAreGreenInsideRedForExcessBlueForMissingGreyForNoData) {
  const fi::ToleranceConfig tolerance = band(-0.0002, 0.0002);
  const fi::Rgb green = fi::deviationColour(0.0, tolerance);
  EXPECT_GT(green[1], green[0]);
  EXPECT_GT(green[1], green[2]);
  for (const double d : {0.0003, 0.0005, 0.01}) {
    const fi::Rgb red = fi::deviationColour(d, tolerance);
    EXPECT_GT(red[0], red[1]) << d;
    EXPECT_GT(red[0], red[2]) << d;
    const fi::Rgb blue = fi::deviationColour(-d, tolerance);
    EXPECT_GT(blue[2], blue[0]) << d;
    EXPECT_GT(blue[2], blue[1]) << d;
  }
  EXPECT_EQ(fi::deviationColour(kNaN, tolerance), fi::kNoDataColour);
  EXPECT_EQ(fi::deviationBand(kNaN, tolerance), fi::kNoDataBand);
  EXPECT_FALSE(fi::inTolerance(kNaN, tolerance));
  EXPECT_EQ(fi::kNoDataColour[0], fi::kNoDataColour[1]);
  EXPECT_EQ(fi::kNoDataColour[1], fi::kNoDataColour[2]);
}

// Farther out of tolerance reads darker and more saturated; every band has its own colour.
TEST(DeviationColours, OuterBandsAreDarkerAndAllBandsDistinct) {
  const auto brightness = [](const fi::Rgb& c) { return c[0] + c[1] + c[2]; };
  for (int k = 1; k < fi::kOutOfToleranceBands; ++k) {
    EXPECT_GT(brightness(fi::bandColour(k)), brightness(fi::bandColour(k + 1))) << k;
    EXPECT_GT(brightness(fi::bandColour(-k)), brightness(fi::bandColour(-k - 1))) << k;
  }
  for (int a = -3; a <= 3; ++a) {
    for (int b = a + 1; b <= 3; ++b) {
      EXPECT_NE(fi::bandColour(a), fi::bandColour(b)) << a << " " << b;
    }
    EXPECT_NE(fi::bandColour(a), fi::kNoDataColour) << a;
  }
  EXPECT_EQ(fi::bandColour(0), (fi::Rgb{60, 175, 75}));
  EXPECT_EQ(fi::bandColour(fi::kNoDataBand), fi::kNoDataColour);
}

TEST(DeviationColours, AsymmetricBandUsesEachSidesOwnTolerance) {
  const fi::ToleranceConfig tolerance = band(-0.0001, 0.0003);  // -0.1 / +0.3 mm
  EXPECT_EQ(fi::deviationBand(0.00025, tolerance), 0);
  EXPECT_EQ(fi::deviationBand(0.0005, tolerance), 1);  // 1-2 x 0.3 mm
  EXPECT_EQ(fi::deviationBand(0.0008, tolerance), 2);  // 2-3 x 0.3 mm
  EXPECT_EQ(fi::deviationBand(0.001, tolerance), 3);
  EXPECT_EQ(fi::deviationBand(-0.00015, tolerance), -1);  // 1-2 x 0.1 mm
  EXPECT_EQ(fi::deviationBand(-0.00025, tolerance), -2);
  EXPECT_EQ(fi::deviationBand(-0.00035, tolerance), -3);
  EXPECT_TRUE(fi::inTolerance(0.0003, tolerance));
  EXPECT_FALSE(fi::inTolerance(-0.00011, tolerance));
}

// A band that does not hold zero (a machining allowance): its width steps the side without a
// tolerance of its own.
TEST(DeviationColours, OffsetBandStepsByItsWidthOnTheSideWithoutTolerance) {
  const fi::ToleranceConfig tolerance = band(0.0001, 0.0003);  // +0.1 .. +0.3 mm
  EXPECT_EQ(fi::deviationBand(0.0002, tolerance), 0);
  EXPECT_EQ(fi::deviationBand(0.0, tolerance), -1);       // 0.1 below, one width = 0.2 mm
  EXPECT_EQ(fi::deviationBand(-0.0002, tolerance), -2);   // 0.3 below
  EXPECT_EQ(fi::deviationBand(-0.00035, tolerance), -3);  // 0.45 below
  EXPECT_EQ(fi::deviationBand(0.0006, tolerance), 1);     // 1-2 x 0.3 mm above nominal
}

TEST(DeviationColours, LegendListsEveryBandWithItsRange) {
  const fi::ToleranceConfig tolerance = band(-0.0001, 0.0002);
  const std::vector<fi::ColourBand> legend = fi::deviationLegend(tolerance);
  ASSERT_EQ(legend.size(), 8u);
  EXPECT_EQ(legend[0].band, -3);
  EXPECT_EQ(legend[0].low, -kInf);
  EXPECT_DOUBLE_EQ(legend[0].high, -0.0003);
  EXPECT_DOUBLE_EQ(legend[1].low, -0.0003);
  EXPECT_DOUBLE_EQ(legend[1].high, -0.0002);
  EXPECT_EQ(legend[3].band, 0);
  EXPECT_EQ(legend[3].label, "in tolerance");
  EXPECT_DOUBLE_EQ(legend[3].low, -0.0001);
  EXPECT_DOUBLE_EQ(legend[3].high, 0.0002);
  EXPECT_DOUBLE_EQ(legend[4].low, 0.0002);
  EXPECT_DOUBLE_EQ(legend[4].high, 0.0004);
  EXPECT_EQ(legend[4].label, "excess 1-2x tolerance");
  EXPECT_DOUBLE_EQ(legend[6].low, 0.0006);
  EXPECT_EQ(legend[6].high, kInf);
  EXPECT_EQ(legend[6].label, "excess >3x tolerance");
  EXPECT_EQ(legend[7].band, fi::kNoDataBand);
  EXPECT_TRUE(std::isnan(legend[7].low));
  EXPECT_EQ(legend[7].colour, fi::kNoDataColour);
  // Each band's colour is the one deviationColour() gives inside its range.
  for (std::size_t i = 1; i + 2 < legend.size(); ++i) {
    const double middle = 0.5 * (legend[i].low + legend[i].high);
    EXPECT_EQ(fi::deviationColour(middle, tolerance), legend[i].colour) << legend[i].label;
    EXPECT_EQ(fi::deviationBand(middle, tolerance), legend[i].band) << legend[i].label;
  }
}

}  // namespace
