// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "inspection_node.h"
#include <ros/ros.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "freeform_inspection");
  freeform_inspection_ros::InspectionNode node(ros::NodeHandle(), ros::NodeHandle("~"));
  if (!node.ok()) {
    return 1;
  }
  ros::spin();
  return 0;
}
