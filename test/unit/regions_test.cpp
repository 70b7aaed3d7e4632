// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// Named regions (regions.h): how a regions file is read and refused, and which region a place
// on the CAD belongs to.
#include "freeform_inspection/regions.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

namespace freeform_inspection {
namespace {

const char* const kTwoRegions = R"(
regions:
  - name: root
    boxes:
      - {min: [-1, -1, -1], max: [1, 1, 0.02]}
    tolerance: {upper: 0.0005, lower: -0.0003}
    min_coverage: 0.5
  - name: clamp
    boxes:
      - {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
      - {min: [0.05, 0, 0.05], max: [0.06, 0.01, 0.06]}
    evaluate: false
    align: false
)";

TEST(Regions, AFileIsReadWithEveryField) {
  const RegionsLoadResult loaded = parseRegions(kTwoRegions);
  ASSERT_TRUE(loaded.status.ok()) << loaded.status.message;
  ASSERT_EQ(loaded.regions.size(), 2u);
  const RegionConfig& root = loaded.regions[0];
  EXPECT_EQ(root.name, "root");
  ASSERT_EQ(root.boxes.size(), 1u);
  EXPECT_EQ(root.boxes[0].max.z(), 0.02);
  EXPECT_TRUE(root.has_tolerance);
  EXPECT_EQ(root.tolerance.upper, 0.0005);
  EXPECT_EQ(root.tolerance.lower, -0.0003);
  EXPECT_TRUE(root.evaluate);
  EXPECT_TRUE(root.align);
  EXPECT_EQ(root.min_coverage, 0.5);
  const RegionConfig& clamp = loaded.regions[1];
  EXPECT_EQ(clamp.boxes.size(), 2u);
  EXPECT_FALSE(clamp.has_tolerance);
  EXPECT_FALSE(clamp.evaluate);
  EXPECT_FALSE(clamp.align);
  const ToleranceConfig part{1e-4, -2e-4};
  EXPECT_EQ(regionTolerance(loaded.regions, 0, part).lower, -0.0003);
  EXPECT_EQ(regionTolerance(loaded.regions, 1, part).lower, -2e-4);  // no band of its own
  EXPECT_EQ(regionTolerance(loaded.regions, -1, part).upper, 1e-4);
}

// Each bad file is refused with a message that names what is wrong, never read in part.
TEST(Regions, BadFilesAreRefusedNamingTheProblem) {
  struct Case {
    const char* yaml;
    const char* names;
  };
  for (const Case& c : {
           Case{"regions: 3", "a list under 'regions:'"},
           Case{"{}", "a list under 'regions:'"},
           Case{"regions: []\nextra: 1", "unknown key 'extra'"},
           Case{"regions:\n  - {name: a, boxes: [{min: [0, 0, 0], max: [1, 1, 1]}], colour: red}",
                "unknown key 'colour'"},
           Case{"regions:\n  - {name: a, boxes: [{min: [0, 0], max: [1, 1, 1]}]}",
                "a list of three numbers"},
           Case{"regions:\n  - {name: a, boxes: [{min: [2, 0, 0], max: [1, 1, 1]}]}", "min is not"},
           Case{"regions:\n  - {name: a}", "region 'a' needs at least one box"},
           Case{"regions:\n  - {boxes: [{min: [0, 0, 0], max: [1, 1, 1]}]}", "needs a name"},
           Case{"regions:\n  - {name: a, boxes: [{min: [0, 0, 0], max: [1, 1, 1]}]}\n"
                "  - {name: a, boxes: [{min: [0, 0, 0], max: [1, 1, 1]}]}",
                "named twice"},
           Case{"regions:\n  - {name: a, boxes: [{min: [0, 0, 0], max: [1, 1, 1]}], "
                "tolerance: {upper: -1, lower: -2}}",
                "tolerance.upper"},
           Case{"regions:\n  - {name: a, boxes: [{min: [0, 0, 0], max: [1, 1, 1]}], "
                "tolerance: {upper: 1}}",
                "tolerance must be a map"},
           Case{"regions:\n  - {name: a, boxes: [{min: [0, 0, 0], max: [1, 1, 1]}], "
                "min_coverage: 2}",
                "min_coverage"},
           Case{"regions:\n  - {name: a, boxes: [{min: [x, 0, 0], max: [1, 1, 1]}]}", "YAML"},
           Case{"regions: [", "YAML"},
       }) {
    SCOPED_TRACE(c.yaml);
    const RegionsLoadResult loaded = parseRegions(c.yaml);
    EXPECT_EQ(loaded.status.code, StatusCode::kInvalidInput);
    EXPECT_NE(loaded.status.message.find(c.names), std::string::npos) << loaded.status.message;
    EXPECT_TRUE(loaded.regions.empty());
  }
}

TEST(Regions, AFileIsReadOrItsPathIsNamed) {
  const std::string path =
      ::testing::TempDir() + "regions_test_" + std::to_string(::getpid()) + ".yaml";
  {
    std::ofstream file(path);
    file << kTwoRegions;
  }
  const RegionsLoadResult loaded = loadRegionsFile(path);
  EXPECT_TRUE(loaded.status.ok()) << loaded.status.message;
  EXPECT_EQ(loaded.regions.size(), 2u);
  std::remove(path.c_str());
  const RegionsLoadResult missing = loadRegionsFile(path);
  EXPECT_EQ(missing.status.code, StatusCode::kInvalidInput);
  EXPECT_NE(missing.status.message.find(path), std::string::npos);
}

// The first region in the file's order with a box holding the place; -1 for the rest.
TEST(Regions, APlaceBelongsToTheFirstRegionThatHoldsIt) {
  const RegionsLoadResult loaded = parseRegions(kTwoRegions);
  ASSERT_TRUE(loaded.status.ok());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Points places = {Eigen::Vector3d(0.005, 0.005, 0.005),  // in both: root comes first
                         Eigen::Vector3d(0.055, 0.005, 0.055),  // clamp's second box
                         Eigen::Vector3d(0.5, 0.5, 0.02),       // root's face, inclusive
                         Eigen::Vector3d(0.5, 0.5, 0.03),       // neither
                         Eigen::Vector3d(nan, 0.0, 0.0)};
  EXPECT_EQ(regionOf(loaded.regions, places), (std::vector<int>{0, 1, 0, -1, -1}));
  std::vector<RegionConfig> reversed = {loaded.regions[1], loaded.regions[0]};
  EXPECT_EQ(regionOf(reversed, places), (std::vector<int>{0, 0, 1, -1, -1}));
  EXPECT_EQ(regionOf({}, places), (std::vector<int>(places.size(), -1)));
}

}  // namespace
}  // namespace freeform_inspection
