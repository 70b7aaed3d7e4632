// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "io_test_util.h"
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include "freeform_inspection/io.h"

namespace freeform_inspection {
namespace {

using io_test::mentions;

// A PCD header as PCL writes it; `fields`, `size` and `type` are the per-field columns.
std::string pcdHeader(const std::string& fields,
                      const std::string& size,
                      const std::string& type,
                      const std::string& count,
                      int width,
                      int height,
                      const std::string& data) {
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " +
         size + "\nTYPE " + type + "\nCOUNT " + count + "\nWIDTH " + std::to_string(width) +
         "\nHEIGHT " + std::to_string(height) + "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
         std::to_string(width * height) + "\nDATA " + data + "\n";
}

class PcdTest : public ::testing::Test {
 protected:
  ScanLoadResult load(const std::string& bytes, double scale = 0.001) {
    return loadScan(io_test::writeBytes(dir_.file("cloud.pcd"), bytes), scale);
  }

  io_test::TempDir dir_;
};

TEST_F(PcdTest, AsciiFloat) {
  const ScanLoadResult result = load(pcdHeader("x y z", "4 4 4", "F F F", "1 1 1", 3, 1, "ascii") +
                                     "1 2 3\n-4 5.5 6\n7 8 9e2\n");
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_points, 3u);
  ASSERT_EQ(result.scan.points.size(), 3u);
  EXPECT_DOUBLE_EQ(result.scan.points[1].x(), -0.004);
  EXPECT_DOUBLE_EQ(result.scan.points[1].y(), 0.0055);
  EXPECT_DOUBLE_EQ(result.scan.points[2].z(), 0.9);
  EXPECT_TRUE(result.scan.faces.empty());
  EXPECT_TRUE(result.scan.normals.empty());
}

TEST_F(PcdTest, BinaryFloatWithExtraFieldsAndNormals) {
  std::string bytes = pcdHeader("x y z intensity normal_x normal_y normal_z",
                                "4 4 4 4 4 4 4",
                                "F F F F F F F",
                                "1 1 1 1 1 1 1",
                                2,
                                1,
                                "binary");
  const float values[2][7] = {{1, 2, 3, 100, 0, 0, 2}, {4, 5, 6, 200, 0, -3, 0}};
  for (const auto& row : values) {
    for (const float v : row) {
      io_test::put(&bytes, v);
    }
  }
  const ScanLoadResult result = load(bytes, 1.0);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.scan.points.size(), 2u);
  EXPECT_EQ(result.scan.points[1], Eigen::Vector3d(4, 5, 6));
  ASSERT_EQ(result.scan.normals.size(), 2u);
  EXPECT_EQ(result.scan.normals[0], Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(result.scan.normals[1], Eigen::Vector3d(0, -1, 0));
}

TEST_F(PcdTest, BinaryDoubleKeepsPrecision) {
  std::string bytes = pcdHeader("x y z", "8 8 8", "F F F", "1 1 1", 2, 1, "binary");
  for (const double v : {1000.000001, -2.0, 3.0, 4.0, 5.0, 6.0}) {
    io_test::put(&bytes, v);
  }
  const ScanLoadResult result = load(bytes, 1.0);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.scan.points.size(), 2u);
  EXPECT_EQ(result.scan.points[0], Eigen::Vector3d(1000.000001, -2.0, 3.0));
}

TEST_F(PcdTest, OrganizedCloudKeepsItsGridWithNaNs) {
  const ScanLoadResult result = load(pcdHeader("x y z", "4 4 4", "F F F", "1 1 1", 2, 2, "ascii") +
                                     "1 2 3\nnan nan nan\n4 5 6\nnan nan nan\n");
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_points, 4u);
  EXPECT_EQ(result.non_finite_removed, 0u);  // the pipeline removes and counts them
  EXPECT_EQ(result.scan.width, 2);
  EXPECT_EQ(result.scan.height, 2);
  EXPECT_TRUE(result.scan.isOrganized());
  ASSERT_EQ(result.scan.points.size(), 4u);
  EXPECT_TRUE(result.scan.points[1].array().isNaN().all());
  EXPECT_TRUE(result.scan.points[3].array().isNaN().all());
  EXPECT_DOUBLE_EQ(result.scan.points[2].z(), 0.006);
}

// A 4 × 3 range image with NaN holes (point and normal) and unit normals elsewhere; every
// coordinate is exact in float32, so a round trip through the file must give them back exactly.
Scan organizedScanWithHoles() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Scan scan;
  scan.width = 4;
  scan.height = 3;
  for (int row = 0; row < scan.height; ++row) {
    for (int column = 0; column < scan.width; ++column) {
      scan.points.emplace_back(0.25 * column, -0.5 * row, 1.0 + 0.125 * (row + column));
      scan.normals.emplace_back(row == 1 ? Eigen::Vector3d(1, 0, 0) : Eigen::Vector3d(0, 0, 1));
    }
  }
  for (const std::size_t hole : {std::size_t{0}, std::size_t{5}, std::size_t{6}, std::size_t{11}}) {
    scan.points[hole] = Eigen::Vector3d::Constant(nan);
    scan.normals[hole] = Eigen::Vector3d::Constant(nan);
  }
  return scan;
}

TEST_F(PcdTest, OrganizedScanRoundTripsThroughSaveScanPcd) {
  const Scan written = organizedScanWithHoles();
  for (const bool binary : {true, false}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    const std::string path = dir_.file(binary ? "grid_binary.pcd" : "grid_ascii.pcd");
    ASSERT_TRUE(saveScanPcd(path, written, binary).ok());
    const ScanLoadResult result = loadScan(path, 1.0);
    ASSERT_TRUE(result.status.ok()) << result.status.message;
    EXPECT_EQ(result.file_points, 12u);
    EXPECT_EQ(result.non_finite_removed, 0u);
    EXPECT_TRUE(result.warnings.empty()) << joinMessages(result.warnings);
    const Scan& scan = result.scan;
    EXPECT_EQ(scan.width, 4);
    EXPECT_EQ(scan.height, 3);
    EXPECT_TRUE(scan.isOrganized());
    ASSERT_EQ(scan.points.size(), written.points.size());
    ASSERT_EQ(scan.normals.size(), written.points.size());
    for (std::size_t i = 0; i < written.points.size(); ++i) {
      SCOPED_TRACE("point " + std::to_string(i));
      if (written.points[i].allFinite()) {
        EXPECT_EQ(scan.points[i], written.points[i]);
        EXPECT_EQ(scan.normals[i], written.normals[i]);
      } else {
        EXPECT_TRUE(scan.points[i].array().isNaN().all()) << scan.points[i].transpose();
        EXPECT_EQ(scan.normals[i], Eigen::Vector3d::Zero());  // unknown normal
      }
    }
  }
}

TEST_F(PcdTest, UnorganizedScanWithNaNsStillDropsThem) {
  Scan written = organizedScanWithHoles();
  written.width = 0;
  written.height = 0;  // written as WIDTH 12, HEIGHT 1
  for (const bool binary : {true, false}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    const std::string path = dir_.file(binary ? "row_binary.pcd" : "row_ascii.pcd");
    ASSERT_TRUE(saveScanPcd(path, written, binary).ok());
    const ScanLoadResult result = loadScan(path, 1.0);
    ASSERT_TRUE(result.status.ok()) << result.status.message;
    EXPECT_EQ(result.file_points, 12u);
    EXPECT_EQ(result.non_finite_removed, 4u);
    ASSERT_EQ(result.warnings.size(), 1u);
    EXPECT_TRUE(mentions(result.warnings[0], "removed 4 non-finite points"));
    const Scan& scan = result.scan;
    EXPECT_EQ(scan.width, 0);
    EXPECT_EQ(scan.height, 0);
    EXPECT_FALSE(scan.isOrganized());
    ASSERT_EQ(scan.points.size(), 8u);
    ASSERT_EQ(scan.normals.size(), 8u);
    std::size_t k = 0;
    for (std::size_t i = 0; i < written.points.size(); ++i) {
      if (written.points[i].allFinite()) {
        EXPECT_EQ(scan.points[k], written.points[i]) << "point " << i;
        EXPECT_EQ(scan.normals[k], written.normals[i]) << "point " << i;
        ++k;
      }
    }
  }
}

TEST_F(PcdTest, OrganizedAllNaNIsInvalid) {
  const ScanLoadResult result = load(pcdHeader("x y z", "4 4 4", "F F F", "1 1 1", 1, 2, "ascii") +
                                     "nan nan nan\nnan nan nan\n");
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "has no finite points (2 stored)"));
}

TEST_F(PcdTest, BinaryCompressedWrittenByPcl) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.push_back(pcl::PointXYZ(1.0f, 2.0f, 3.0f));
  cloud.push_back(pcl::PointXYZ(-1.0f, 0.5f, 10.0f));
  cloud.push_back(pcl::PointXYZ(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f));
  const std::string path = dir_.file("compressed.PCD");
  ASSERT_EQ(pcl::io::savePCDFileBinaryCompressed(path, cloud), 0);
  const ScanLoadResult result = loadScan(path, 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_points, 3u);
  EXPECT_EQ(result.non_finite_removed, 1u);
  ASSERT_EQ(result.scan.points.size(), 2u);
  EXPECT_DOUBLE_EQ(result.scan.points[1].z(), 0.01);
}

TEST_F(PcdTest, MissingXFieldIsNamed) {
  const ScanLoadResult result =
      load(pcdHeader("y z", "4 4", "F F", "1 1", 1, 1, "ascii") + "1 2\n");
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "has no 'x' field"));
}

TEST_F(PcdTest, IntegerCoordinatesAreRejected) {
  const ScanLoadResult result =
      load(pcdHeader("x y z", "4 4 4", "I I I", "1 1 1", 1, 1, "ascii") + "1 2 3\n");
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "field 'x' has PCL datatype"));
}

TEST_F(PcdTest, MalformedHeaderIsInvalid) {
  const ScanLoadResult result = load("this is not a point cloud\n");
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "cannot read PCD"));
}

TEST_F(PcdTest, TruncatedBinaryIsInvalid) {
  std::string bytes = pcdHeader("x y z", "4 4 4", "F F F", "1 1 1", 100, 1, "binary");
  for (int i = 0; i < 30; ++i) {
    io_test::put(&bytes, 1.0f);
  }
  const ScanLoadResult result = load(bytes);
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "cloud.pcd"));
}

TEST_F(PcdTest, ZeroPointsIsInvalid) {
  const ScanLoadResult result = load(pcdHeader("x y z", "4 4 4", "F F F", "1 1 1", 0, 1, "ascii"));
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "(0 stored)"));
}

TEST_F(PcdTest, AllNaNIsInvalid) {
  const ScanLoadResult result = load(pcdHeader("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "ascii") +
                                     "nan nan nan\nnan nan nan\n");
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "has no finite points (2 stored)"));
}

}  // namespace
}  // namespace freeform_inspection
