// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// rostest client with ~fixed_frame:=world: the part pose of a scan in "scanner" is carried into
// "world" through tf2 at the scan's stamp; a scan in a frame tf does not know is refused naming
// both frames and the stamp, and the node keeps serving.
#include <string>

#include "rostest_helpers.h"
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "freeform_inspection/io.h"
#include <freeform_inspection/Inspect.h>

namespace freeform_inspection_rostest {
namespace {

using freeform_inspection::Inspect;

Inspect::Response call(const Inspect::Request& request) {
  Inspect srv;
  srv.request = request;
  EXPECT_TRUE(ros::service::waitForService(nodeName() + "/inspect", kWait));
  EXPECT_TRUE(ros::service::call(nodeName() + "/inspect", srv));
  return srv.response;
}

TEST(FixedFrame, ScanIsMovedIntoTheFixedFrameAndAnUnknownFrameIsRefused) {
  // world → scanner: a turn of 30° about z and an offset, published once (static, latched).
  const Eigen::Isometry3d T_world_scanner = Eigen::Translation3d(0.4, -0.2, 1.1) *
                                            Eigen::AngleAxisd(M_PI / 6.0, Eigen::Vector3d::UnitZ());
  geometry_msgs::TransformStamped mount = tf2::eigenToTransform(T_world_scanner);
  mount.header.frame_id = "world";
  mount.header.stamp = ros::Time(0);
  mount.child_frame_id = "scanner";
  tf2_ros::StaticTransformBroadcaster broadcaster;
  broadcaster.sendTransform(mount);

  const Inspect::Response moved = call(cloudRequest(sampleCloud()));
  ASSERT_EQ(moved.status, Inspect::Response::PASS) << moved.message;
  EXPECT_EQ(moved.report.header.frame_id, "world");
  EXPECT_EQ(moved.report.transform.header.frame_id, "world");
  const Eigen::Isometry3d part_in_world = tf2::transformToEigen(moved.report.transform);
  // The sample's part pose in the scanner frame, carried into the world by the mount.
  expectSamplePose(T_world_scanner.inverse() * part_in_world, "part pose moved back to scanner");

  sensor_msgs::PointCloud2 lost = sampleCloud();
  lost.header.frame_id = "nowhere";
  const Inspect::Response refused = call(cloudRequest(lost));
  EXPECT_EQ(refused.status, Inspect::Response::ERROR);
  EXPECT_EQ(refused.report.error_code, "TF_ERROR");
  for (const char* word : {"'nowhere'", "'world'", "1234.5"}) {
    EXPECT_NE(refused.message.find(word), std::string::npos) << word << ": " << refused.message;
  }
  EXPECT_EQ(call(cloudRequest(sampleCloud())).status, Inspect::Response::PASS)
      << "the node must keep serving after a refused frame";

  // ~input/crop_box (the .test file) is a box of the world: clutter 0.4 m in front of the part
  // (1.5 m up in the world) is cropped, the part is not. Tested in the scanner's frame the box
  // would hold nothing of the scan (its z there is 0.04-0.11 m).
  freeform_inspection::Points points =
      freeform_inspection::loadScan(param("sample_scan"), 1.0).scan.points;
  const std::size_t part = points.size();
  for (int i = 0; i < 300; ++i) {
    points.emplace_back(-0.17 + 0.0001 * i, 0.0, 0.5);
  }
  const Inspect::Response cropped = call(cloudRequest(toCloud(points, "scanner")));
  EXPECT_EQ(cropped.status, Inspect::Response::PASS) << cropped.message;
  EXPECT_EQ(cropped.report.counts.cropped, 300u);
  EXPECT_EQ(cropped.report.counts.scan_points, part);
}

}  // namespace
}  // namespace freeform_inspection_rostest
