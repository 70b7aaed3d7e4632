// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/scan_cleaning.h"

#include <cmath>
#include <limits>
#include <random>

#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

constexpr unsigned kSeed = 7;
const Eigen::Vector3d kHalf(0.05, 0.03, 0.02);  // a 100 × 60 × 40 mm part

BoundingBox modelBounds() {
  return computeBoundingBox(test::makeBox(kHalf).vertices);
}

Scan boxScan(int count) {
  Scan scan;
  scan.points = test::sampleBoxSurface(kHalf, count, kSeed);
  return scan;
}

TEST(CleanScan, KeepsAGoodScanAndRemovesAndCountsNonFinitePoints) {
  Scan scan = boxScan(500);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  scan.points.insert(scan.points.begin() + 10, Eigen::Vector3d(nan, 0, 0));
  scan.points.emplace_back(0, inf, 0);
  scan.points.emplace_back(0, 0, -inf);
  const CleanScanResult result = cleanScan(scan, modelBounds(), InputConfig());
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.non_finite, 3u);
  EXPECT_EQ(result.scan.points.size(), 500u);
  for (const auto& p : result.scan.points) {
    EXPECT_TRUE(p.allFinite());
  }
}

TEST(CleanScan, ReindexesFacesAndDropsThoseTouchingNonFinitePoints) {
  Scan scan;
  scan.points = {{0, 0, 0}, {std::nan(""), 0, 0}, {0.01, 0, 0}, {0, 0.01, 0}, {0, 0, 0.01}};
  scan.faces = {{0, 1, 2}, {0, 2, 3}, {2, 3, 4}};
  const CleanScanResult result = cleanScan(scan, modelBounds(), InputConfig());
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.scan.faces.size(), 2u);
  EXPECT_EQ(result.scan.faces[0], Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(result.scan.faces[1], Eigen::Vector3i(1, 2, 3));
}

TEST(CleanScan, EmptyAndAllNanAreInvalidInput) {
  EXPECT_EQ(cleanScan(Scan(), modelBounds(), InputConfig()).status.code, StatusCode::kInvalidInput);
  Scan all_nan;
  all_nan.points.assign(4, Eigen::Vector3d::Constant(std::nan("")));
  const CleanScanResult result = cleanScan(all_nan, modelBounds(), InputConfig());
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_NE(result.status.message.find("no finite points (4 received)"), std::string::npos)
      << result.status.message;
}

TEST(CleanScan, TooFewPointsIsDegenerate) {
  Scan two;
  two.points = {{0, 0, 0}, {0.05, 0.01, 0}};
  const CleanScanResult result = cleanScan(two, modelBounds(), InputConfig());
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput);
  EXPECT_NE(result.status.message.find("2 finite points"), std::string::npos);
}

TEST(CleanScan, CollinearAndPlanarScansAreDegenerate) {
  Scan line;
  Scan plane;
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (int i = 0; i < 200; ++i) {
    const double t = u(rng);
    line.points.emplace_back(t, 0.5 * t, -0.2 * t);
    plane.points.emplace_back(u(rng), u(rng), 0.0);
  }
  const CleanScanResult as_line = cleanScan(line, modelBounds(), InputConfig());
  EXPECT_EQ(as_line.status.code, StatusCode::kDegenerateInput);
  EXPECT_NE(as_line.status.message.find("collinear"), std::string::npos);
  const CleanScanResult as_plane = cleanScan(plane, modelBounds(), InputConfig());
  EXPECT_EQ(as_plane.status.code, StatusCode::kDegenerateInput);
  EXPECT_NE(as_plane.status.message.find("planar"), std::string::npos);
}

TEST(CleanScan, DuplicatedPointsAreDegenerateNotACrash) {
  Scan same;
  same.points.assign(100, Eigen::Vector3d(0.01, 0.02, 0.03));
  EXPECT_EQ(cleanScan(same, modelBounds(), InputConfig()).status.code,
            StatusCode::kDegenerateInput);
}

TEST(CleanScan, ScanInMillimetresAgainstCadInMetresIsAUnitsMismatch) {
  Scan scan = boxScan(300);
  for (auto& p : scan.points) {
    p *= 1000.0;
  }
  const CleanScanResult too_big = cleanScan(scan, modelBounds(), InputConfig());
  EXPECT_EQ(too_big.status.code, StatusCode::kUnitsMismatch);
  EXPECT_NE(too_big.status.message.find("units"), std::string::npos);
  for (auto& p : scan.points) {
    p *= 1e-6;  // now 1000× too small
  }
  EXPECT_EQ(cleanScan(scan, modelBounds(), InputConfig()).status.code, StatusCode::kUnitsMismatch);
}

TEST(CleanScan, PartialScanOfAFifthOfThePartIsAccepted) {
  Scan scan = boxScan(2000);
  Scan partial;
  for (const auto& p : scan.points) {
    if (p.x() > 0.03) {
      partial.points.push_back(p);
    }
  }
  EXPECT_TRUE(cleanScan(partial, modelBounds(), InputConfig()).status.ok());
}

TEST(CleanScan, ScansAboveTheConfiguredPointCapAreRefused) {
  InputConfig config;
  config.max_points = 100;
  const CleanScanResult result = cleanScan(boxScan(101), modelBounds(), config);
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_NE(result.status.message.find("input.max_points = 100"), std::string::npos);
}

TEST(CleanScan, FaceIndexOutOfRangeIsInvalidInput) {
  Scan scan = boxScan(10);
  scan.faces = {{0, 1, 10}};
  EXPECT_EQ(cleanScan(scan, modelBounds(), InputConfig()).status.code, StatusCode::kInvalidInput);
}

TEST(CropToBox, DropsWhatLiesOutsideAndCountsItKeepingTheGrid) {
  Scan scan;
  scan.width = 3;
  scan.height = 2;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  scan.points = {
      {0, 0, 0}, {0.2, 0, 0}, {nan, 0, 0}, {0.05, -0.05, 0.09}, {0, 0, -0.2}, {0, 0, 0.1}};
  std::size_t cropped = 0;
  const Scan inside =
      cropToBox(scan, {-0.1, -0.1, -0.1, 0.1, 0.1, 0.1}, Eigen::Isometry3d::Identity(), &cropped);
  EXPECT_EQ(cropped, 2u);  // x = 0.2 and z = -0.2; the NaN was not a point, z = 0.1 is on the box
  ASSERT_EQ(inside.points.size(), 6u);
  EXPECT_EQ(inside.width, 3);
  EXPECT_EQ(inside.height, 2);
  for (const std::size_t kept : {0u, 3u, 5u}) {
    EXPECT_EQ(inside.points[kept], scan.points[kept]) << kept;
  }
  for (const std::size_t gone : {1u, 2u, 4u}) {
    EXPECT_FALSE(inside.points[gone].allFinite()) << gone;
  }
  const CleanScanResult cleaned = cleanScan(inside, modelBounds(), InputConfig());
  EXPECT_EQ(cleaned.non_finite, 3u);  // the pipeline subtracts the cropped ones
  // No box: nothing changes.
  const Scan same = cropToBox(scan, {}, Eigen::Isometry3d::Identity(), &cropped);
  EXPECT_EQ(cropped, 0u);
  EXPECT_FALSE(same.points[1].hasNaN());
}

TEST(CropToBox, ABoxInAnotherFrameIsTestedThere) {
  // box_from_scan turns a quarter about z, then moves 1 m down: (0.2, 0, 1) → (0, 0.2, 0),
  // inside the box; (0, 0.2, 1) → (−0.2, 0, 0) and (0.2, 0, 0) → (0, 0.2, −1), outside.
  Scan scan;
  scan.points = {{0.2, 0.0, 1.0}, {0.0, 0.2, 1.0}, {0.2, 0.0, 0.0}};
  const Eigen::Isometry3d box_from_scan = Eigen::Translation3d(0.0, 0.0, -1.0) *
                                          Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitZ());
  std::size_t cropped = 0;
  const Scan inside = cropToBox(scan, {-0.1, 0.1, -0.1, 0.1, 0.3, 0.1}, box_from_scan, &cropped);
  EXPECT_EQ(cropped, 2u);
  EXPECT_TRUE(inside.points[0].allFinite());
  EXPECT_FALSE(inside.points[1].allFinite());
  EXPECT_FALSE(inside.points[2].allFinite());
  // The same box in the scan's own frame holds none of them.
  cropToBox(scan, {-0.1, 0.1, -0.1, 0.1, 0.3, 0.1}, Eigen::Isometry3d::Identity(), &cropped);
  EXPECT_EQ(cropped, 3u);
}

}  // namespace
}  // namespace freeform_inspection
