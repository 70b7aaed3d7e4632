// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "parameters.h"
#include <actionlib/server/simple_action_server.h>
#include <diagnostic_updater/diagnostic_updater.h>
#include <pcl_msgs/PolygonMesh.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include "freeform_inspection/comparison_points.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/regions.h"
#include <freeform_inspection/Inspect.h>
#include <freeform_inspection/InspectAction.h>
#include <freeform_inspection/LoadModel.h>

namespace freeform_inspection_ros {

/// One scan as it arrived: a cloud on `scan` or a mesh on `scan_mesh`; at most one is set.
struct ScanMessage {
  sensor_msgs::PointCloud2ConstPtr cloud;
  pcl_msgs::PolygonMeshConstPtr mesh;

  explicit operator bool() const { return cloud || mesh; }
  /// The mesh's header (its cloud's when the mesh's own names no frame), else the cloud's.
  const std_msgs::Header& header() const;
};

/// The inspection node: converts and delegates, all geometry is in the core.
///
/// Subscribes `scan` (PointCloud2) and `scan_mesh` (pcl_msgs/PolygonMesh); publishes the part pose
/// on tf, `~deviation`, `~deviation_viz`,
/// `~defects`, `~model_marker` and `~result` (latched), and diagnostics; serves `~inspect` and
/// `~load_model` on their own callback queue and thread, and the `~inspect_action` action on
/// another, so a long inspection blocks neither incoming scans nor a cancel. With
/// `~auto_inspect` a worker thread inspects the latest scan; scans that arrive while it is busy
/// replace the waiting one and are counted as dropped. One inspection runs at a time, whoever
/// asked. The same class runs as the standalone node and as the nodelet.
/// What a model is inspected with besides the settings: its named regions and comparison points,
/// both in its frame, so replaced with it.
struct ModelPlan {
  std::vector<freeform_inspection::RegionConfig> regions;
  std::vector<freeform_inspection::ComparisonPointConfig> comparison_points;
  freeform_inspection::DatumPrecedence datum_precedence;
};

class InspectionNode {
 public:
  /// @param pnh private node handle ("~"): parameters, outputs and services live under it.
  InspectionNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  ~InspectionNode();
  InspectionNode(const InspectionNode&) = delete;
  InspectionNode& operator=(const InspectionNode&) = delete;

  /// False when the parameters were invalid; the reasons were logged with ROS_FATAL.
  bool ok() const { return ok_; }

 private:
  using InspectServer = actionlib::SimpleActionServer<freeform_inspection::InspectAction>;
  /// Told when a node-level stage starts ("converting", "inspecting", "publishing") with the
  /// progress so far; returns false to cancel the inspection before that stage.
  using StageHook = std::function<bool(const std::string& stage, double progress)>;

  void onScan(ScanMessage scan);
  bool onInspect(freeform_inspection::Inspect::Request& request,
                 freeform_inspection::Inspect::Response& response);
  bool onLoadModel(freeform_inspection::LoadModel::Request& request,
                   freeform_inspection::LoadModel::Response& response);
  void startActionServer();
  void onInspectAction(const freeform_inspection::InspectGoalConstPtr& goal);
  /// Waits for the running inspection to end; false when a cancel (or shutdown) came first.
  bool waitForTurn(std::unique_lock<std::timed_mutex>* turn);
  /// Action feedback for `stage`; false when the client asked to cancel.
  bool actionStage(const std::string& stage, double progress);
  void finishAction(const freeform_inspection::InspectionReport& report);
  void autoInspectLoop();
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  /// Loads and installs a model with its plan (named regions, comparison points); returns ""
  /// or the reason it failed.
  std::string installModel(const std::string& uri,
                           const std::string& units,
                           const std::string& id,
                           ModelPlan plan,
                           freeform_inspection::LoadModel::Response* summary);
  /// Runs one inspection, publishes its outputs and returns the report. A given `scan` is
  /// inspected instead of the one the request names (auto_inspect hands the received message on
  /// without a copy).
  freeform_inspection::InspectionReport inspectAndPublish(
      const freeform_inspection::Inspect::Request& request, const ScanMessage& scan = {});
  /// inspectAndPublish() for a caller that holds `inspect_mutex_`; a cancelled run (report
  /// error_code CANCELLED) publishes nothing.
  freeform_inspection::InspectionReport inspectAndPublishLocked(
      const freeform_inspection::Inspect::Request& request,
      const StageHook& stage,
      const ScanMessage& scan = {});
  freeform_inspection::InspectionReport inspect(
      const freeform_inspection::Inspect::Request& request,
      ScanMessage scan,
      const std::shared_ptr<const freeform_inspection::Model>& model,
      const ModelPlan& plan,
      const StageHook& stage);
  /// The refusal of a request that cannot be inspected (no or another model), or nothing.
  std::optional<freeform_inspection::InspectionReport> refusal(
      const freeform_inspection::Inspect::Request& request,
      const std::shared_ptr<const freeform_inspection::Model>& model) const;
  /// Sets `scan` to the scan the request names (the last received, its mesh or its cloud), or
  /// returns the refusal: none received yet, both a cloud and a mesh, or more points than
  /// input/max_points (refused before anything is copied or converted).
  std::optional<freeform_inspection::InspectionReport> requestedScan(
      const freeform_inspection::Inspect::Request& request, ScanMessage* scan) const;
  /// The request's initial_guess as T_cad_scan of a scan in `scan_frame` at `stamp` (in *pose;
  /// left empty when the request gives none), or the refusal: a rotation that is no unit
  /// quaternion, another child frame than ~part_frame, a frame tf cannot move into the scan's,
  /// an alignment that needs a guess without one, an unknown alignment.
  std::optional<freeform_inspection::InspectionReport> initialPose(
      const freeform_inspection::Inspect::Request& request,
      const std_msgs::Header& scan_header,
      std::optional<Eigen::Isometry3d>* pose) const;
  /// The refusal of a (vertex) cloud of more than input/max_points points, or nothing.
  std::optional<freeform_inspection::InspectionReport> tooBig(const sensor_msgs::PointCloud2& cloud,
                                                              const std_msgs::Header& header) const;
  /// Writes the report files under ~report_dir and lists them in `report`.
  void archive(const freeform_inspection::InspectionResult& result,
               const freeform_inspection::PipelineConfig& pipeline,
               const freeform_inspection::Model& model,
               const ScanMessage& scan,
               const std::string& scan_name,
               freeform_inspection::InspectionReport* report) const;
  void publish(const freeform_inspection::InspectionResult& result,
               const freeform_inspection::ToleranceBands& tolerance,
               const freeform_inspection::InspectionReport& report);
  ScanMessage lastScan() const;
  bool stopping() const;
  std::shared_ptr<const freeform_inspection::Model> model() const;

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;
  NodeConfig config_;
  bool ok_ = false;

  mutable std::mutex model_mutex_;
  std::shared_ptr<const freeform_inspection::Model> model_;
  ModelPlan plan_;           // model_'s, replaced with it
  std::string model_error_;  // why no model is loaded, for the Inspect answer

  // One inspection at a time (service, action or auto); timed so a queued goal can be cancelled.
  std::timed_mutex inspect_mutex_;

  mutable std::mutex scan_mutex_;
  std::condition_variable scan_arrived_;
  ScanMessage last_scan_;
  ScanMessage pending_scan_;  // auto_inspect: waiting for the worker
  bool stopping_ = false;
  std::uint64_t scans_received_ = 0;
  std::uint64_t scans_dropped_ = 0;

  mutable std::mutex stats_mutex_;
  std::uint64_t inspections_ = 0;
  std::uint64_t cancelled_ = 0;
  freeform_inspection::InspectionReport last_report_;

  ros::Subscriber scan_sub_;
  ros::Subscriber scan_mesh_sub_;
  ros::Publisher marker_pub_;
  ros::Publisher result_pub_;
  ros::Publisher pose_pub_;
  ros::Publisher deviation_pub_;
  ros::Publisher deviation_viz_pub_;
  ros::Publisher defects_pub_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::StaticTransformBroadcaster tf_static_broadcaster_;
  tf2_ros::Buffer tf_buffer_;  // scans into ~fixed_frame
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  diagnostic_updater::Updater diagnostics_;
  ros::Timer diagnostics_timer_;
  ros::CallbackQueue service_queue_;
  ros::ServiceServer inspect_srv_;
  ros::ServiceServer load_model_srv_;
  std::unique_ptr<ros::AsyncSpinner> service_spinner_;
  // The action has its own queue so goals and cancels arrive while a service call runs.
  ros::CallbackQueue action_queue_;
  std::unique_ptr<InspectServer> action_server_;
  std::unique_ptr<ros::AsyncSpinner> action_spinner_;
  std::thread auto_worker_;
};

}  // namespace freeform_inspection_ros
