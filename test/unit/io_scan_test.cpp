// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <cmath>
#include <limits>
#include <string>

#include "io_test_util.h"
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"

namespace freeform_inspection {
namespace {

using io_test::mentions;
using io_test::PlyEncoding;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

class ScanTest : public ::testing::Test {
 protected:
  io_test::TempDir dir_;
};

TEST_F(ScanTest, NonFinitePointsAreRemovedAndCounted) {
  const Points points = {{1, 2, 3}, {kNaN, 0, 0}, {4, 5, 6}, {0, kInf, 0}, {7, 8, 9}};
  for (const auto encoding : {PlyEncoding::kAscii, PlyEncoding::kBinaryLittleEndian}) {
    const ScanLoadResult result = loadScan(
        io_test::writeBytes(dir_.file("s.ply"), io_test::plyBytes(points, {}, encoding, false)),
        0.001);
    ASSERT_TRUE(result.status.ok()) << result.status.message;
    EXPECT_EQ(result.file_points, 5u);
    EXPECT_EQ(result.non_finite_removed, 2u);
    ASSERT_EQ(result.scan.points.size(), 3u);
    EXPECT_DOUBLE_EQ(result.scan.points[1].x(), 0.004);
    EXPECT_DOUBLE_EQ(result.scan.points[2].z(), 0.009);
    ASSERT_FALSE(result.warnings.empty());
    EXPECT_TRUE(mentions(result.warnings[0], "removed 2 non-finite points"));
  }
}

TEST_F(ScanTest, AllNaNScanIsInvalid) {
  const Points points = {{kNaN, kNaN, kNaN}, {kNaN, 0, 0}, {0, 0, kNaN}};
  const std::string path = io_test::writeBytes(
      dir_.file("nan.ply"), io_test::plyBytes(points, {}, PlyEncoding::kBinaryLittleEndian, true));
  const ScanLoadResult result = loadScan(path, 1.0);
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(
      mentions(result.status.message, "scan '" + path + "' has no finite points (3 stored)"));
}

TEST_F(ScanTest, FacesUsingRemovedPointsAreDroppedAndOthersReindexed) {
  const Points points = {{0, 0, 0}, {kNaN, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  const ScanLoadResult result = loadScan(
      io_test::writeBytes(
          dir_.file("mesh.ply"),
          io_test::plyBytes(
              points, {{0, 1, 2}, {0, 2, 3}, {2, 4, 3}}, PlyEncoding::kBinaryLittleEndian, false)),
      1.0);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.non_finite_removed, 1u);
  ASSERT_EQ(result.scan.faces.size(), 2u);
  EXPECT_EQ(result.scan.faces[0], Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(result.scan.faces[1], Eigen::Vector3i(1, 3, 2));
  ASSERT_EQ(result.warnings.size(), 2u);
  EXPECT_TRUE(mentions(result.warnings[1], "dropped 1 faces that used non-finite points"));
}

TEST_F(ScanTest, NormalsStayAlignedWithTheKeptPoints) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nend_header\n"
      "nan 0 0 1 0 0\n1 2 3 0 2 0\n4 5 6 0 0 0\n";
  const ScanLoadResult result = loadScan(io_test::writeBytes(dir_.file("n.ply"), text), 1.0);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.scan.points.size(), 2u);
  ASSERT_EQ(result.scan.normals.size(), 2u);
  EXPECT_EQ(result.scan.normals[0], Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(result.scan.normals[1], Eigen::Vector3d::Zero());
  EXPECT_TRUE(mentions(result.warnings.back(), "1 normals are zero or non-finite"));
}

TEST_F(ScanTest, OverflowingScaleCountsAsNonFinite) {
  const Points points = {{1e300, 0, 0}, {1, 1, 1}};
  const ScanLoadResult result = loadScan(
      io_test::writeBytes(dir_.file("big.ply"),
                          io_test::plyBytes(points, {}, PlyEncoding::kBinaryLittleEndian, true)),
      1e10);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.non_finite_removed, 1u);
}

TEST_F(ScanTest, StlScanIsWeldedAndKeepsFaces) {
  const ScanLoadResult result =
      loadScan(io_test::writeBytes(dir_.file("scan.stl"),
                                   io_test::binaryStl(io_test::makeCube(10.0), "scanner mesh")),
               0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_points, 36u);  // corners as stored
  EXPECT_EQ(result.scan.points.size(), 8u);
  EXPECT_EQ(result.scan.faces.size(), 12u);
  EXPECT_TRUE(result.scan.normals.empty());
}

TEST_F(ScanTest, EmptyAsciiStlScanHasNoPoints) {
  const ScanLoadResult result =
      loadScan(io_test::writeBytes(dir_.file("e.stl"), "solid e\nendsolid e\n"), 1.0);
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "has no finite points (0 stored)"));
}

}  // namespace
}  // namespace freeform_inspection
