// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <memory>
#include <mutex>
#include <string>

#include "parameters.h"
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>

#include "freeform_inspection/model.h"
#include <freeform_inspection/Inspect.h>
#include <freeform_inspection/LoadModel.h>

namespace freeform_inspection_ros {

/// The inspection node: converts and delegates, all geometry is in the core.
///
/// Subscribes `scan`; publishes `~model_marker` and `~result` (latched); serves `~inspect` and
/// `~load_model` on their own callback queue and thread, so a long inspection does not block
/// incoming scans.
class InspectionNode {
 public:
  /// @param pnh private node handle ("~"): parameters, outputs and services live under it.
  InspectionNode(ros::NodeHandle nh, ros::NodeHandle pnh);

  /// False when the parameters were invalid; the reasons were logged with ROS_FATAL.
  bool ok() const { return ok_; }

 private:
  void onScan(const sensor_msgs::PointCloud2ConstPtr& cloud);
  bool onInspect(freeform_inspection::Inspect::Request& request,
                 freeform_inspection::Inspect::Response& response);
  bool onLoadModel(freeform_inspection::LoadModel::Request& request,
                   freeform_inspection::LoadModel::Response& response);

  /// Loads and installs a model; returns "" or the reason it failed.
  std::string installModel(const std::string& uri,
                           const std::string& units,
                           const std::string& id,
                           freeform_inspection::LoadModel::Response* summary);
  freeform_inspection::InspectionReport inspect(
      const freeform_inspection::Inspect::Request& request);
  sensor_msgs::PointCloud2ConstPtr lastScan() const;

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;
  NodeConfig config_;
  bool ok_ = false;

  std::shared_ptr<const freeform_inspection::Model> model_;  // only touched on service_queue_
  std::string model_error_;  // why no model is loaded, for the Inspect answer

  mutable std::mutex scan_mutex_;
  sensor_msgs::PointCloud2ConstPtr last_scan_;

  ros::Subscriber scan_sub_;
  ros::Publisher marker_pub_;
  ros::Publisher result_pub_;
  ros::CallbackQueue service_queue_;
  ros::ServiceServer inspect_srv_;
  ros::ServiceServer load_model_srv_;
  std::unique_ptr<ros::AsyncSpinner> service_spinner_;
};

}  // namespace freeform_inspection_ros
