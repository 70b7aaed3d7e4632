// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "inspection_node.h"

#include <cmath>
#include <utility>

#include "conversions.h"
#include <visualization_msgs/Marker.h>

#include "freeform_inspection/pipeline.h"

namespace freeform_inspection_ros {

namespace fi = freeform_inspection;
using freeform_inspection::Inspect;
using freeform_inspection::InspectionReport;
using freeform_inspection::LoadModel;

InspectionNode::InspectionNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : nh_(std::move(nh)), pnh_(std::move(pnh)) {
  const NodeConfigResult loaded = loadNodeConfig(pnh_);
  for (const auto& warning : loaded.warnings) {
    ROS_WARN_STREAM(warning);
  }
  for (const auto& error : loaded.errors) {
    ROS_FATAL_STREAM("invalid parameter: " << error);
  }
  if (!loaded.errors.empty()) {
    return;
  }
  config_ = loaded.config;
  marker_pub_ = pnh_.advertise<visualization_msgs::Marker>("model_marker", 1, /*latch=*/true);
  result_pub_ = pnh_.advertise<InspectionReport>("result", 1, /*latch=*/true);
  // Queue size 1: the latest scan wins, older ones are dropped.
  scan_sub_ = nh_.subscribe("scan", 1, &InspectionNode::onScan, this);
  if (config_.model.empty()) {
    model_error_ = "no model loaded: set ~model and ~model_units or call ~load_model";
    ROS_WARN_STREAM(model_error_);
  } else {
    model_error_ = installModel(config_.model, config_.model_units, config_.model_id, nullptr);
    if (!model_error_.empty()) {
      ROS_ERROR_STREAM(model_error_ << " (the node keeps running; use ~load_model)");
    }
  }
  ros::NodeHandle service_nh(pnh_);
  service_nh.setCallbackQueue(&service_queue_);
  inspect_srv_ = service_nh.advertiseService("inspect", &InspectionNode::onInspect, this);
  load_model_srv_ = service_nh.advertiseService("load_model", &InspectionNode::onLoadModel, this);
  service_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &service_queue_);
  service_spinner_->start();
  ok_ = true;
}

void InspectionNode::onScan(const sensor_msgs::PointCloud2ConstPtr& cloud) {
  std::lock_guard<std::mutex> lock(scan_mutex_);
  last_scan_ = cloud;
}

sensor_msgs::PointCloud2ConstPtr InspectionNode::lastScan() const {
  std::lock_guard<std::mutex> lock(scan_mutex_);
  return last_scan_;
}

std::string InspectionNode::installModel(const std::string& uri,
                                         const std::string& units,
                                         const std::string& id,
                                         LoadModel::Response* summary) {
  const auto scale = fi::unitScale(units);
  if (!scale) {
    return "model units must be 'm', 'mm' or 'in' (got '" + units + "')";
  }
  const std::string path = resolveModelPath(uri);
  if (path.empty()) {
    return "cannot resolve model URL '" + uri + "'";
  }
  fi::ModelLoadResult loaded = fi::loadModel(path, *scale, id, config_.pipeline.descriptor);
  for (const auto& warning : loaded.warnings) {
    ROS_WARN_STREAM(warning);
  }
  if (!loaded.status.ok()) {
    return loaded.status.message;
  }
  model_ = loaded.model;
  const Eigen::Vector3d extent = model_->bounds().extent();
  ROS_INFO_STREAM("loaded model '" << id << "' from " << path << ": " << model_->mesh().faces.size()
                                   << " faces, extent " << extent.transpose() << " m");
  marker_pub_.publish(modelMarker(*model_, config_.part_frame));
  if (summary != nullptr) {
    summary->vertices = static_cast<std::uint32_t>(model_->mesh().vertices.size());
    summary->faces = static_cast<std::uint32_t>(model_->mesh().faces.size());
    summary->extent = {extent.x(), extent.y(), extent.z()};
    summary->diagonal = extent.norm();
  }
  return "";
}

bool InspectionNode::onLoadModel(LoadModel::Request& request, LoadModel::Response& response) {
  const std::string id = request.model_id.empty() ? config_.model_id : request.model_id;
  const std::string error = installModel(request.path, request.units, id, &response);
  response.success = error.empty();
  response.message = error.empty() ? "loaded model '" + id + "'" : error;
  if (!error.empty()) {
    ROS_WARN_STREAM("~load_model refused: " << error);
  }
  return true;  // the outcome is in the response, never a failed call
}

InspectionReport InspectionNode::inspect(const Inspect::Request& request) {
  if (!model_) {
    return errorReport("MODEL_NOT_LOADED", model_error_);
  }
  if (!request.model_id.empty() && request.model_id != model_->id()) {
    return errorReport(
        "UNKNOWN_MODEL",
        "model '" + request.model_id + "' is not loaded (loaded: '" + model_->id() + "')");
  }
  sensor_msgs::PointCloud2ConstPtr cloud =
      request.use_last_scan ? lastScan()
                            : boost::make_shared<sensor_msgs::PointCloud2>(request.cloud);
  if (!cloud) {
    return errorReport(
        "NO_SCAN",
        "use_last_scan is set but no cloud has arrived on '" + scan_sub_.getTopic() + "'");
  }
  const CloudConversion converted = cloudToScan(*cloud);
  if (!converted.status.ok()) {
    return errorReport(errorCode(converted.status.code), converted.status.message);
  }
  fi::PipelineConfig pipeline = config_.pipeline;
  if (std::isfinite(request.tolerance_upper) && request.tolerance_upper > 0.0) {
    pipeline.tolerance.upper = request.tolerance_upper;
  }
  if (std::isfinite(request.tolerance_lower) && request.tolerance_lower < 0.0) {
    pipeline.tolerance.lower = request.tolerance_lower;
  }
  const fi::InspectionResult result = fi::inspect(*model_, converted.scan, pipeline);
  InspectionReport report = toReport(result, cloud->header, config_.part_frame);
  report.tolerance_upper = pipeline.tolerance.upper;
  report.tolerance_lower = pipeline.tolerance.lower;
  return report;
}

bool InspectionNode::onInspect(Inspect::Request& request, Inspect::Response& response) {
  InspectionReport report = inspect(request);
  report.part_id = request.part_id;
  report.model_id = model_ ? model_->id() : "";
  if (report.status == InspectionReport::ERROR) {
    ROS_WARN_STREAM("inspection " << report.error_code << ": " << report.message);
  }
  result_pub_.publish(report);
  response.status = report.status;
  response.message = report.message;
  response.report = report;
  return true;  // the outcome is in response.status, never a failed call
}

}  // namespace freeform_inspection_ros
