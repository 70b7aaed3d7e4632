// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// Comparison points read from a deviation map of known values on a 1 mm plate (test_shapes.h):
// which points are read, what they read, and how each verdict is decided.
#include "freeform_inspection/comparison_points.h"

#include <cmath>
#include <string>
#include <vector>

#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/mesh_query.h"

namespace freeform_inspection {
namespace {

constexpr double kHalfThickness = 0.0005;  // a plate 100 x 100 x 1 mm
constexpr double kSpacing = 0.0002;        // scan points every 0.2 mm
constexpr double kBump = 0.00005;          // the top face's points lie 0.05 mm above it

const MeshQuery& plate() {
  static const MeshQuery query(test::makeBox({0.05, 0.05, kHalfThickness}));
  return query;
}

// Points on a grid of |x|, |y| ≤ 2 mm: on the top face raised by kBump (deviation kBump), on
// the bottom face as it is (deviation 0).
DeviationMap plateScan() {
  DeviationMap map;
  for (int i = -10; i <= 10; ++i) {
    for (int j = -10; j <= 10; ++j) {
      map.points.emplace_back(i * kSpacing, j * kSpacing, kHalfThickness + kBump);
      map.deviation.push_back(static_cast<float>(kBump));
      map.points.emplace_back(i * kSpacing, j * kSpacing, -kHalfThickness);
      map.deviation.push_back(0.0f);
    }
  }
  return map;
}

ComparisonPointConfig pointAt(const std::string& name, const Eigen::Vector3d& position) {
  ComparisonPointConfig point;
  point.name = name;
  point.position = position;
  return point;
}

ToleranceConfig band(double half_width) {
  ToleranceConfig tolerance;
  tolerance.upper = half_width;
  tolerance.lower = -half_width;
  return tolerance;
}

TEST(ComparisonPoints, ReadTheMedianOfThisSidesPointsWithinTheRadius) {
  const DeviationMap map = plateScan();
  ComparisonPointConfig top = pointAt("top", {0.0, 0.0, kHalfThickness});
  top.radius = 0.0005;
  // Placed 0.3 mm above the bottom face: moved onto it.
  ComparisonPointConfig bottom = pointAt("bottom", {0.0004, 0.0, -kHalfThickness - 0.0003});
  bottom.radius = 0.0005;
  const std::vector<ComparisonPointResult> read =
      readComparisonPoints({top, bottom}, {}, band(1e-4), plate(), map, 1.0);
  ASSERT_EQ(read.size(), 2u);
  // Grid points within 0.5 mm of the centre: i² + j² ≤ 2.5² on the 0.2 mm grid.
  std::size_t inside = 0;
  for (int i = -10; i <= 10; ++i) {
    for (int j = -10; j <= 10; ++j) {
      inside += i * i + j * j <= 6 ? 1 : 0;  // 6.25 rounds down: no grid point lies between
    }
  }
  EXPECT_EQ(read[0].points, inside);  // the bottom face's, 1 mm away, are not read
  EXPECT_DOUBLE_EQ(read[0].deviation, static_cast<double>(static_cast<float>(kBump)));
  EXPECT_DOUBLE_EQ(read[0].spread, 0.0);
  EXPECT_NEAR((read[0].nominal - Eigen::Vector3d(0.0, 0.0, kHalfThickness)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(read[0].normal.z(), 1.0, 1e-12);
  EXPECT_NEAR(read[0].off_surface, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(read[0].radius, 0.0005);
  EXPECT_TRUE(read[0].measured());
  // The bottom one reads the bottom face's points about (0.4 mm, 0): i from -0.5 to 4.5.
  std::size_t below = 0;
  for (int i = -10; i <= 10; ++i) {
    for (int j = -10; j <= 10; ++j) {
      below += (i - 2) * (i - 2) + j * j <= 6 ? 1 : 0;
    }
  }
  EXPECT_EQ(read[1].points, below);
  EXPECT_DOUBLE_EQ(read[1].deviation, 0.0);
  EXPECT_NEAR(read[1].normal.z(), -1.0, 1e-12);
  EXPECT_NEAR(read[1].off_surface, 0.0003, 1e-12);
  EXPECT_NEAR(read[1].nominal.z(), -kHalfThickness, 1e-12);
}

TEST(ComparisonPoints, TooFewPointsOrAPlaceFarOffTheSurfaceAreNotMeasured) {
  const DeviationMap map = plateScan();
  ComparisonPointConfig lone = pointAt("lone", {0.0, 0.0, kHalfThickness});
  lone.radius = 0.00005;  // only the grid point under it
  ComparisonPointConfig outside = pointAt("outside", {0.04, 0.04, kHalfThickness});
  // 10 mm above the plate with the default radius of 1 mm: in other units or frame.
  const ComparisonPointConfig far = pointAt("far", {0.0, 0.0, kHalfThickness + 0.01});
  const std::vector<ComparisonPointResult> read =
      readComparisonPoints({lone, outside, far}, {}, band(1e-4), plate(), map, 0.001);
  ASSERT_EQ(read.size(), 3u);
  EXPECT_EQ(read[0].points, 1u);
  EXPECT_FALSE(read[0].measured());
  EXPECT_TRUE(std::isnan(read[0].deviation));
  EXPECT_NE(read[0].verdict_reason.find("1 scan point(s) within"), std::string::npos)
      << read[0].verdict_reason;
  EXPECT_EQ(read[1].points, 0u);
  EXPECT_FALSE(read[1].measured());
  EXPECT_FALSE(read[2].measured());
  EXPECT_NEAR(read[2].off_surface, 0.01, 1e-12);
  EXPECT_NE(read[2].verdict_reason.find("off the CAD surface"), std::string::npos)
      << read[2].verdict_reason;
  for (ComparisonPointResult point : read) {
    judgeComparisonPoint(0.0, &point);
    EXPECT_EQ(point.verdict, Verdict::kNotEvaluated) << point.name;
  }
}

TEST(ComparisonPoints, BandOfItsOwnOrOfItsRegionOrOfThePart) {
  const DeviationMap map = plateScan();
  ComparisonPointConfig own = pointAt("own", {0.0, 0.0, kHalfThickness});
  own.has_tolerance = true;
  own.tolerance = band(3e-5);
  const ComparisonPointConfig in_region = pointAt("in_region", {0.001, 0.0, kHalfThickness});
  const ComparisonPointConfig rest = pointAt("rest", {-0.001, 0.0, kHalfThickness});
  RegionConfig region;
  region.name = "right";
  region.boxes.push_back({Eigen::Vector3d(0.0005, -1.0, -1.0), Eigen::Vector3d(1.0, 1.0, 1.0)});
  region.has_tolerance = true;
  region.tolerance = band(2e-4);
  const std::vector<ComparisonPointResult> read =
      readComparisonPoints({own, in_region, rest}, {region}, band(1e-4), plate(), map, 0.0005);
  ASSERT_EQ(read.size(), 3u);
  EXPECT_DOUBLE_EQ(read[0].tolerance.upper, 3e-5);
  EXPECT_DOUBLE_EQ(read[1].tolerance.upper, 2e-4);
  EXPECT_DOUBLE_EQ(read[2].tolerance.upper, 1e-4);
  std::vector<Verdict> verdicts;
  for (ComparisonPointResult point : read) {
    judgeComparisonPoint(0.0, &point);
    verdicts.push_back(point.verdict);
  }
  EXPECT_EQ(verdicts, (std::vector<Verdict>{Verdict::kFail, Verdict::kPass, Verdict::kPass}));
}

TEST(ComparisonPoints, MeasurementUncertaintyDecidesOnlyWhatItProves) {
  // Read 0.05 mm: against bands and an uncertainty U (ISO 14253-1's zones).
  struct Case {
    double half_band;
    double u;
    Verdict expected;
  };
  for (const Case& c : {Case{1e-4, 0.0, Verdict::kPass},
                        Case{1e-4, 4e-5, Verdict::kPass},  // 0.05 ≤ 0.1 - 0.04
                        Case{1e-4, 6e-5, Verdict::kNotEvaluated},
                        Case{4e-5, 0.0, Verdict::kFail},
                        Case{4e-5, 2e-5, Verdict::kNotEvaluated},  // 0.05 ≤ 0.04 + 0.02
                        Case{4e-5, 5e-6, Verdict::kFail}}) {
    ComparisonPointResult point;
    point.name = "p";
    point.points = 10;
    point.deviation = 5e-5;
    point.tolerance = band(c.half_band);
    judgeComparisonPoint(c.u, &point);
    EXPECT_EQ(point.verdict, c.expected)
        << "band " << c.half_band << ", U " << c.u << ": " << point.verdict_reason;
  }
}

TEST(ComparisonPoints, FilesAreReadStrictly) {
  const ComparisonPointsLoadResult good = parseComparisonPoints(
      "points:\n"
      "  - name: LE_1\n"
      "    position: [0.01, 0.02, 0.03]\n"
      "    tolerance: {upper: 0.0001, lower: -0.00005}\n"
      "    radius: 0.002\n"
      "  - name: TE_1\n"
      "    position: [0, 0, 0]\n");
  ASSERT_TRUE(good.status.ok()) << good.status.message;
  ASSERT_EQ(good.points.size(), 2u);
  EXPECT_EQ(good.points[0].name, "LE_1");
  EXPECT_EQ(good.points[0].position, Eigen::Vector3d(0.01, 0.02, 0.03));
  EXPECT_TRUE(good.points[0].has_tolerance);
  EXPECT_DOUBLE_EQ(good.points[0].tolerance.lower, -0.00005);
  EXPECT_DOUBLE_EQ(good.points[0].radius, 0.002);
  EXPECT_FALSE(good.points[1].has_tolerance);
  EXPECT_DOUBLE_EQ(good.points[1].radius, 0.0);

  const std::vector<std::pair<std::string, std::string>> bad = {
      {"points:\n  - name: a\n    position: [0, 0, 0]\n    radus: 0.001\n", "unknown key 'radus'"},
      {"points:\n  - name: a\n", "position must be a list of three numbers"},
      {"points:\n  - name: a\n    position: [0, 0]\n", "position must be a list of three"},
      {"points:\n  - name: a\n    position: [0, 0, 0]\n  - name: a\n    position: [1, 0, 0]\n",
       "named twice"},
      {"points:\n  - position: [0, 0, 0]\n", "needs a name"},
      {"points:\n  - name: a\n    position: [0, 0, 0]\n    radius: -1\n", "radius must be"},
      {"points:\n  - name: a\n    position: [0, 0, 0]\n    tolerance: {upper: 0.001}\n",
       "tolerance must be a map"},
      {"regions: []\n", "a list under 'points:'"},
      {"points: [\n", "YAML error"}};
  for (const auto& [text, message] : bad) {
    const ComparisonPointsLoadResult result = parseComparisonPoints(text);
    EXPECT_EQ(result.status.code, StatusCode::kInvalidInput) << text;
    EXPECT_NE(result.status.message.find(message), std::string::npos)
        << text << " -> " << result.status.message;
    EXPECT_TRUE(result.points.empty());
  }
  const ComparisonPointsLoadResult missing = loadComparisonPointsFile("/nonexistent/points.yaml");
  EXPECT_EQ(missing.status.code, StatusCode::kInvalidInput);
  EXPECT_NE(missing.status.message.find("comparison points file"), std::string::npos);
}

}  // namespace
}  // namespace freeform_inspection
