// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "rostest_helpers.h"

#include <cmath>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <tf2_eigen/tf2_eigen.h>

#include "freeform_inspection/io.h"

namespace freeform_inspection_rostest {

tf2_ros::Buffer* tf_buffer = nullptr;

std::string param(const std::string& name) {
  std::string value;
  EXPECT_TRUE(ros::param::get("~" + name, value)) << "missing test parameter ~" << name;
  return value;
}

std::string nodeName() {
  std::string name;
  ros::param::param<std::string>("~node", name, "/freeform_inspection");
  return name;
}

sensor_msgs::PointCloud2 toCloud(const freeform_inspection::Points& points,
                                 const std::string& frame) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header.frame_id = frame;
  cloud.header.stamp = ros::Time(1234.5);
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  modifier.setPointCloud2FieldsByString(1, "xyz");
  modifier.resize(points.size());
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x");
  for (const auto& p : points) {
    x[0] = static_cast<float>(p.x());
    x[1] = static_cast<float>(p.y());
    x[2] = static_cast<float>(p.z());
    ++x;
  }
  return cloud;
}

sensor_msgs::PointCloud2 sampleCloud() {
  const auto scan = freeform_inspection::loadScan(param("sample_scan"), 1.0);
  EXPECT_TRUE(scan.status.ok()) << scan.status.message;
  return toCloud(scan.scan.points, "scanner");
}

Eigen::Isometry3d sampleTruth() {
  std::ifstream file(param("sample_truth"));
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      file >> m(r, c);
    }
  }
  EXPECT_TRUE(file) << "cannot read " << param("sample_truth");
  return Eigen::Isometry3d(m);
}

double angleDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}

void expectSamplePose(const Eigen::Isometry3d& part_in_scan, const std::string& what) {
  const Eigen::Isometry3d truth = sampleTruth().inverse();
  EXPECT_LT(angleDeg(part_in_scan, truth), kPoseToleranceDeg) << what;
  EXPECT_LT((part_in_scan.translation() - truth.translation()).norm(), kPoseToleranceM) << what;
}

std::optional<Eigen::Isometry3d> partOnTf(const ros::Time& stamp) {
  std::string error;
  if (tf_buffer == nullptr ||
      !tf_buffer->canTransform("scanner", "part", stamp, ros::Duration(5.0), &error)) {
    ADD_FAILURE() << "no transform scanner → part at " << stamp << ": " << error;
    return std::nullopt;
  }
  return tf2::transformToEigen(tf_buffer->lookupTransform("scanner", "part", stamp));
}

freeform_inspection::Inspect::Request cloudRequest(const sensor_msgs::PointCloud2& cloud,
                                                   const std::string& part_id) {
  freeform_inspection::Inspect::Request request;
  request.use_last_scan = false;
  request.cloud = cloud;
  request.part_id = part_id;
  request.tolerance_upper = std::numeric_limits<double>::quiet_NaN();
  request.tolerance_lower = std::numeric_limits<double>::quiet_NaN();
  return request;
}

freeform_inspection::Inspect::Response callInspect(freeform_inspection::Inspect::Request request) {
  freeform_inspection::Inspect srv;
  srv.request = std::move(request);
  EXPECT_TRUE(ros::service::waitForService(nodeName() + "/inspect", kWait));
  EXPECT_TRUE(ros::service::call(nodeName() + "/inspect", srv))
      << "the call itself must never fail";
  return srv.response;
}

bool waitUntil(const std::function<bool()>& done, const ros::Duration& timeout) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout.toSec());
  while (!done()) {
    if (ros::WallTime::now() > deadline || !ros::ok()) {
      return false;
    }
    ros::WallDuration(0.02).sleep();  // a poll period, not a wait for a result
  }
  return true;
}

}  // namespace freeform_inspection_rostest
