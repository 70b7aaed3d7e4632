// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// PointCloud2 → Scan (src/ros/conversions.cpp) on malformed messages: every inconsistency in the
// layout or the x/y/z fields is refused with kInvalidInput naming the quantity, never read out of
// bounds. No ROS master: cloudToScan is a plain function.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "conversions.h"
#include <gtest/gtest.h>

namespace freeform_inspection_ros {
namespace {

using sensor_msgs::PointField;

PointField field(const std::string& name, std::uint32_t offset, std::uint8_t datatype) {
  PointField f;
  f.name = name;
  f.offset = offset;
  f.datatype = datatype;
  f.count = 1;
  return f;
}

// `width` × `height` points (x, y, z, padding) as float32 at a 16-byte point step.
sensor_msgs::PointCloud2 goodCloud(std::uint32_t width, std::uint32_t height = 1) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header.frame_id = "scanner";
  cloud.width = width;
  cloud.height = height;
  cloud.fields = {field("x", 0, PointField::FLOAT32),
                  field("y", 4, PointField::FLOAT32),
                  field("z", 8, PointField::FLOAT32)};
  cloud.point_step = 16;
  cloud.row_step = width * cloud.point_step;
  cloud.data.assign(std::size_t{cloud.row_step} * height, 0);
  for (std::uint32_t i = 0; i < width * height; ++i) {
    const float xyz[3] = {0.01F * static_cast<float>(i), 1.0F, -2.0F};
    std::memcpy(cloud.data.data() + std::size_t{i} * cloud.point_step, xyz, sizeof(xyz));
  }
  return cloud;
}

void expectRefused(const sensor_msgs::PointCloud2& cloud, const std::string& words) {
  const CloudConversion result = cloudToScan(cloud);
  EXPECT_EQ(result.status.code, fi::StatusCode::kInvalidInput) << words;
  EXPECT_NE(result.status.message.find("invalid PointCloud2"), std::string::npos)
      << result.status.message;
  EXPECT_NE(result.status.message.find(words), std::string::npos) << result.status.message;
  EXPECT_TRUE(result.scan.points.empty()) << words;
}

// After a refusal the same function converts a good cloud (there is no state, but a crash or an
// out-of-bounds read on the bad one would show here or under AddressSanitizer).
void expectGoodStillConverts() {
  const CloudConversion good = cloudToScan(goodCloud(5));
  ASSERT_TRUE(good.status.ok()) << good.status.message;
  ASSERT_EQ(good.scan.points.size(), 5u);
  EXPECT_FLOAT_EQ(static_cast<float>(good.scan.points[4].x()), 0.04F);
  EXPECT_EQ(good.scan.points[4].y(), 1.0);
  EXPECT_EQ(good.scan.points[4].z(), -2.0);
}

TEST(CloudToScan, GoodCloudsConvertIncludingPaddedRowsAndGrids) {
  expectGoodStillConverts();
  sensor_msgs::PointCloud2 grid = goodCloud(4, 3);
  const CloudConversion organized = cloudToScan(grid);
  ASSERT_TRUE(organized.status.ok()) << organized.status.message;
  EXPECT_EQ(organized.scan.width, 4);
  EXPECT_EQ(organized.scan.height, 3);
  EXPECT_TRUE(organized.scan.isOrganized());

  // Rows padded to 80 bytes: row_step > width · point_step is legal.
  sensor_msgs::PointCloud2 padded = goodCloud(4, 2);
  std::vector<std::uint8_t> data(160, 0);
  std::memcpy(data.data(), padded.data.data(), 64);
  std::memcpy(data.data() + 80, padded.data.data() + 64, 64);
  padded.row_step = 80;
  padded.data = data;
  const CloudConversion rows = cloudToScan(padded);
  ASSERT_TRUE(rows.status.ok()) << rows.status.message;
  ASSERT_EQ(rows.scan.points.size(), 8u);
  EXPECT_FLOAT_EQ(static_cast<float>(rows.scan.points[4].x()), 0.04F);
}

TEST(CloudToScan, EmptyCloudConvertsToAnEmptyScanForTheCleaningStageToRefuse) {
  for (const auto& [width, height] : {std::pair<std::uint32_t, std::uint32_t>{0, 1}, {5, 0}}) {
    sensor_msgs::PointCloud2 cloud = goodCloud(width, height);
    const CloudConversion result = cloudToScan(cloud);
    EXPECT_TRUE(result.status.ok()) << result.status.message;
    EXPECT_TRUE(result.scan.points.empty());
  }
}

TEST(CloudToScan, DataShorterThanRowStepTimesHeightIsRefused) {
  sensor_msgs::PointCloud2 cloud = goodCloud(10, 2);
  cloud.data.resize(cloud.data.size() - 1);
  expectRefused(cloud, "data holds 319 bytes, less than row_step 160 * height 2");
  cloud = goodCloud(10);
  cloud.height = 7;  // height lies: the data holds one row
  expectRefused(cloud, "less than row_step 160 * height 7");
  cloud = goodCloud(10);
  cloud.width = 4000000000U;  // width lies: row_step no longer covers a row
  expectRefused(cloud, "row_step 160 < width 4000000000 * point_step 16");
  expectGoodStillConverts();
}

TEST(CloudToScan, RowStepOrPointStepTooSmallIsRefused) {
  sensor_msgs::PointCloud2 cloud = goodCloud(10);
  cloud.row_step = 100;
  expectRefused(cloud, "row_step 100 < width 10 * point_step 16");
  cloud = goodCloud(10);
  cloud.point_step = 8;  // z at offset 8 no longer fits in a point
  expectRefused(cloud, "field 'z' at offset 8 does not fit in point_step 8");
  cloud = goodCloud(10);
  cloud.point_step = 0;  // every point at the same address
  expectRefused(cloud, "does not fit in point_step 0");
  expectGoodStillConverts();
}

TEST(CloudToScan, FieldOffsetNearTheTopOfUint32DoesNotWrapAround) {
  // offset + 4 overflows 32 bits to 2, which "fits" a 16-byte point: it must not be read.
  sensor_msgs::PointCloud2 cloud = goodCloud(10);
  cloud.fields[1].offset = std::numeric_limits<std::uint32_t>::max() - 1;
  expectRefused(cloud, "field 'y' at offset 4294967294 does not fit in point_step 16");
  cloud.fields[1].datatype = PointField::FLOAT64;
  cloud.fields[1].offset = std::numeric_limits<std::uint32_t>::max() - 3;
  expectRefused(cloud, "field 'y' at offset 4294967292 does not fit");
  expectGoodStillConverts();
}

TEST(CloudToScan, MissingCoordinateFieldsAreNamed) {
  for (std::size_t missing = 0; missing < 3; ++missing) {
    sensor_msgs::PointCloud2 cloud = goodCloud(10);
    const std::string name = cloud.fields[missing].name;
    cloud.fields.erase(cloud.fields.begin() + static_cast<std::ptrdiff_t>(missing));
    expectRefused(cloud, "cloud has no '" + name + "' field");
  }
  sensor_msgs::PointCloud2 renamed = goodCloud(10);
  renamed.fields[0].name = "X";  // names are case-sensitive, as in PCL
  expectRefused(renamed, "cloud has no 'x' field");
  sensor_msgs::PointCloud2 none = goodCloud(10);
  none.fields.clear();
  expectRefused(none, "cloud has no 'x' field");
  expectGoodStillConverts();
}

TEST(CloudToScan, NonFloatCoordinatesAreRefusedNamingTheDatatype) {
  const std::uint8_t types[] = {PointField::INT8,
                                PointField::UINT8,
                                PointField::INT16,
                                PointField::UINT16,
                                PointField::INT32,
                                PointField::UINT32,
                                0,
                                99};
  for (const std::uint8_t type : types) {
    sensor_msgs::PointCloud2 cloud = goodCloud(10);
    cloud.fields[0].datatype = type;
    expectRefused(
        cloud,
        "field 'x' has datatype " + std::to_string(type) + "; only FLOAT32 (7) and FLOAT64 (8)");
  }
  expectGoodStillConverts();
}

TEST(CloudToScan, DuplicatedCoordinateFieldNamesAreRefused) {
  // Two 'x' fields: which one is the coordinate is a guess, so the cloud is refused.
  sensor_msgs::PointCloud2 cloud = goodCloud(10);
  cloud.fields.push_back(field("x", 12, PointField::FLOAT32));
  expectRefused(cloud, "field 'x' appears 2 times");
  // Duplicated fields that are not coordinates are ignored like any other extra field.
  sensor_msgs::PointCloud2 extra = goodCloud(10);
  extra.fields.push_back(field("intensity", 12, PointField::FLOAT32));
  extra.fields.push_back(field("intensity", 12, PointField::FLOAT32));
  EXPECT_TRUE(cloudToScan(extra).status.ok());
  expectGoodStillConverts();
}

TEST(CloudToScan, BigEndianIsRefused) {
  sensor_msgs::PointCloud2 cloud = goodCloud(10);
  cloud.is_bigendian = true;
  expectRefused(cloud, "big-endian clouds are not supported");
  expectGoodStillConverts();
}

TEST(CloudToScan, NonFiniteValuesAreKeptForThePipelineToCount) {
  sensor_msgs::PointCloud2 cloud = goodCloud(3);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  std::memcpy(cloud.data.data(), &nan, sizeof(nan));
  std::memcpy(cloud.data.data() + 16 + 4, &inf, sizeof(inf));
  const CloudConversion result = cloudToScan(cloud);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.scan.points.size(), 3u);
  EXPECT_TRUE(std::isnan(result.scan.points[0].x()));
  EXPECT_TRUE(std::isinf(result.scan.points[1].y()));
  EXPECT_TRUE(result.scan.points[2].allFinite());
}

}  // namespace
}  // namespace freeform_inspection_ros
