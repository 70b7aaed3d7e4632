// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// One gtest client for every rostest of the node; each .test file picks its cases with
// --gtest_filter (node, action, nodelet, auto_inspect).
#include "rostest_helpers.h"
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2_ros/transform_listener.h>

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "inspection_node_test");
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);  // subscriptions, tf and action feedback arrive while a test waits
  spinner.start();
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  freeform_inspection_rostest::tf_buffer = &buffer;
  return RUN_ALL_TESTS();
}
