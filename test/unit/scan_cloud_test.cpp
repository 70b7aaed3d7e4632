// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// Scan → PointCloud2 (scanToCloud, src/ros/conversions.cpp), as virtual_scanner_node publishes
// it: x y z FLOAT32, the organized grid and its NaN kept, read back by cloudToScan unchanged.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "conversions.h"
#include <gtest/gtest.h>

namespace freeform_inspection_ros {
namespace {

using sensor_msgs::PointField;

fi::Scan organizedScan() {
  fi::Scan scan;
  scan.width = 3;
  scan.height = 2;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  scan.points = {{0.25, -0.5, 1.0},
                 {nan, nan, nan},
                 {0.125, 0.0, 2.0},
                 {-1.5, 0.75, 0.5},
                 {1.0, 2.0, 3.0},
                 {nan, nan, nan}};
  return scan;
}

TEST(ScanToCloud, OrganizedScanKeepsGridNanAndHeader) {
  std_msgs::Header header;
  header.frame_id = "scanner";
  header.stamp = ros::Time(12.5);
  const fi::Scan scan = organizedScan();
  const sensor_msgs::PointCloud2 cloud = scanToCloud(scan, header);
  EXPECT_EQ(cloud.header.frame_id, "scanner");
  EXPECT_EQ(cloud.header.stamp, ros::Time(12.5));
  EXPECT_EQ(cloud.width, 3U);
  EXPECT_EQ(cloud.height, 2U);
  ASSERT_EQ(cloud.fields.size(), 3U);
  for (std::uint32_t i = 0; i < 3; ++i) {
    EXPECT_EQ(cloud.fields[i].name, std::string(1, "xyz"[i]));
    EXPECT_EQ(cloud.fields[i].offset, 4 * i);
    EXPECT_EQ(cloud.fields[i].datatype, PointField::FLOAT32);
    EXPECT_EQ(cloud.fields[i].count, 1U);
  }
  EXPECT_EQ(cloud.point_step, 12U);
  EXPECT_EQ(cloud.row_step, 36U);
  EXPECT_EQ(cloud.data.size(), 72U);
  EXPECT_FALSE(cloud.is_dense);
  EXPECT_FALSE(cloud.is_bigendian);

  const CloudConversion back = cloudToScan(cloud);
  ASSERT_TRUE(back.status.ok()) << back.status.message;
  EXPECT_EQ(back.scan.width, 3);
  EXPECT_EQ(back.scan.height, 2);
  ASSERT_EQ(back.scan.points.size(), scan.points.size());
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    if (scan.points[i].allFinite()) {
      EXPECT_EQ(back.scan.points[i], scan.points[i]) << i;  // exact in float
    } else {
      EXPECT_TRUE(back.scan.points[i].array().isNaN().all()) << i;
    }
  }
}

TEST(ScanToCloud, UnorganizedScanIsOneDenseRow) {
  fi::Scan scan;
  scan.points = {{1.0, 2.0, 3.0}, {4.0, 5.0, 6.0}};
  const sensor_msgs::PointCloud2 cloud = scanToCloud(scan, std_msgs::Header());
  EXPECT_EQ(cloud.width, 2U);
  EXPECT_EQ(cloud.height, 1U);
  EXPECT_TRUE(cloud.is_dense);
  const CloudConversion back = cloudToScan(cloud);
  ASSERT_TRUE(back.status.ok()) << back.status.message;
  EXPECT_EQ(back.scan.width, 0);
  ASSERT_EQ(back.scan.points.size(), 2U);
  EXPECT_EQ(back.scan.points[1], Eigen::Vector3d(4.0, 5.0, 6.0));
}

}  // namespace
}  // namespace freeform_inspection_ros
