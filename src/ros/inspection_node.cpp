// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "inspection_node.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <utility>

#include "conversions.h"
#include "model_access.h"
#include "report_files.h"
#include "result_messages.h"
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include "freeform_inspection/content_hash.h"
#include "freeform_inspection/pipeline.h"

namespace freeform_inspection_ros {

namespace fi = freeform_inspection;
using freeform_inspection::Inspect;
using freeform_inspection::InspectionReport;
using freeform_inspection::LoadModel;

namespace {

// Action progress at the start of each stage; fi::inspect() reports its own stages inside the
// inspecting span.
constexpr double kConvertingProgress = 0.02;
constexpr double kInspectingProgress = 0.05;
constexpr double kPublishingProgress = 0.95;

// The configured pipeline with the request's tolerance band where it sets one.
fi::PipelineConfig requestPipeline(const fi::PipelineConfig& configured,
                                   const Inspect::Request& request) {
  fi::PipelineConfig pipeline = configured;
  if (std::isfinite(request.tolerance_upper) && request.tolerance_upper > 0.0) {
    pipeline.tolerance.upper = request.tolerance_upper;
  }
  if (std::isfinite(request.tolerance_lower) && request.tolerance_lower < 0.0) {
    pipeline.tolerance.lower = request.tolerance_lower;
  }
  return pipeline;
}

bool hasCloud(const sensor_msgs::PointCloud2& cloud) {
  return std::uint64_t{cloud.width} * cloud.height > 0 || !cloud.data.empty();
}

}  // namespace

const std_msgs::Header& ScanMessage::header() const {
  if (mesh) {
    return mesh->header.frame_id.empty() ? mesh->cloud.header : mesh->header;
  }
  return cloud->header;
}

InspectionNode::InspectionNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    // Named by the private namespace: inside a nodelet manager the process name is the manager's.
    : nh_(std::move(nh)), pnh_(std::move(pnh)), diagnostics_(nh_, pnh_, pnh_.getNamespace()) {
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
  if (!config_.fixed_frame.empty()) {
    tf_listener_ = std::make_unique<tf2_ros::TransformListener>(tf_buffer_, nh_);
  }
  marker_pub_ = pnh_.advertise<visualization_msgs::Marker>("model_marker", 1, /*latch=*/true);
  result_pub_ = pnh_.advertise<InspectionReport>("result", 1, /*latch=*/true);
  pose_pub_ = pnh_.advertise<geometry_msgs::PoseWithCovarianceStamped>("pose", 1, /*latch=*/true);
  deviation_pub_ = pnh_.advertise<sensor_msgs::PointCloud2>("deviation", 1);
  // Latched: a viewer started after the inspection still shows its result (rviz).
  deviation_viz_pub_ = pnh_.advertise<sensor_msgs::PointCloud2>("deviation_viz", 1, /*latch=*/true);
  defects_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("defects", 1, /*latch=*/true);
  diagnostics_.setHardwareID("freeform_inspection");
  diagnostics_.add("inspection", this, &InspectionNode::diagnose);
  diagnostics_timer_ = nh_.createTimer(ros::Duration(1.0),
                                       [this](const ros::TimerEvent&) { diagnostics_.update(); });
  // Queue size 1: the latest scan wins, older ones are dropped.
  scan_sub_ = nh_.subscribe<sensor_msgs::PointCloud2>(
      "scan", 1, [this](const sensor_msgs::PointCloud2ConstPtr& cloud) {
        onScan(ScanMessage{cloud, {}});
      });
  scan_mesh_sub_ = nh_.subscribe<pcl_msgs::PolygonMesh>(
      "scan_mesh", 1, [this](const pcl_msgs::PolygonMeshConstPtr& mesh) {
        onScan(ScanMessage{{}, mesh});
      });
  // Under the lock: in a nodelet manager the diagnostics timer may already be reading it.
  std::string model_error;
  if (config_.model.empty()) {
    model_error = "no model loaded: set ~model and ~model_units or call ~load_model";
    ROS_WARN_STREAM(model_error);
  } else {
    model_error = installModel(config_.model,
                               config_.model_units,
                               config_.model_id,
                               {config_.pipeline.regions,
                                config_.pipeline.comparison_points,
                                config_.pipeline.datum_precedence},
                               nullptr);
    if (!model_error.empty()) {
      ROS_ERROR_STREAM(model_error << " (the node keeps running; use ~load_model)");
    }
  }
  {
    std::lock_guard<std::mutex> lock(model_mutex_);
    model_error_ = model_error;
  }
  ros::NodeHandle service_nh(pnh_);
  service_nh.setCallbackQueue(&service_queue_);
  inspect_srv_ = service_nh.advertiseService("inspect", &InspectionNode::onInspect, this);
  load_model_srv_ = service_nh.advertiseService("load_model", &InspectionNode::onLoadModel, this);
  service_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &service_queue_);
  service_spinner_->start();
  startActionServer();
  if (config_.auto_inspect) {
    auto_worker_ = std::thread(&InspectionNode::autoInspectLoop, this);
  }
  ok_ = true;
}

InspectionNode::~InspectionNode() {
  {
    std::lock_guard<std::mutex> lock(scan_mutex_);
    stopping_ = true;
  }
  scan_arrived_.notify_all();
  if (auto_worker_.joinable()) {
    auto_worker_.join();
  }
  if (action_spinner_) {
    action_spinner_->stop();
  }
  action_server_.reset();  // joins its thread: a running inspection finishes first
  if (service_spinner_) {
    service_spinner_->stop();
  }
}

void InspectionNode::onScan(ScanMessage scan) {
  {
    std::lock_guard<std::mutex> lock(scan_mutex_);
    last_scan_ = scan;
    ++scans_received_;
    if (config_.auto_inspect) {
      if (pending_scan_) {
        ++scans_dropped_;  // the worker is busy: the latest scan wins
      }
      pending_scan_ = std::move(scan);
    }
  }
  scan_arrived_.notify_one();
}

void InspectionNode::autoInspectLoop() {
  Inspect::Request request;
  request.use_last_scan = false;
  request.tolerance_upper = std::numeric_limits<double>::quiet_NaN();
  request.tolerance_lower = std::numeric_limits<double>::quiet_NaN();
  while (true) {
    ScanMessage scan;
    {
      std::unique_lock<std::mutex> lock(scan_mutex_);
      scan_arrived_.wait(lock, [this] { return stopping_ || static_cast<bool>(pending_scan_); });
      if (stopping_) {
        return;
      }
      scan = std::exchange(pending_scan_, ScanMessage{});
    }
    const InspectionReport report = inspectAndPublish(request, scan);
    ROS_INFO_STREAM("auto_inspect: " << statusName(report.status) << ": " << report.message);
  }
}

std::shared_ptr<const fi::Model> InspectionNode::model() const {
  std::lock_guard<std::mutex> lock(model_mutex_);
  return model_;
}

void InspectionNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  InspectionReport last;
  std::uint64_t inspections = 0;
  std::uint64_t cancelled = 0;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    last = last_report_;
    inspections = inspections_;
    cancelled = cancelled_;
  }
  std::uint64_t received = 0;
  std::uint64_t dropped = 0;
  {
    std::lock_guard<std::mutex> lock(scan_mutex_);
    received = scans_received_;
    dropped = scans_dropped_;
  }
  const auto current = model();
  using Status = diagnostic_msgs::DiagnosticStatus;
  if (!current) {
    std::lock_guard<std::mutex> lock(model_mutex_);
    status.summary(Status::ERROR, model_error_);
  } else if (inspections == 0) {
    status.summary(Status::OK, "model '" + current->id() + "' loaded, no inspection yet");
  } else if (last.status == InspectionReport::ERROR) {
    status.summary(Status::WARN, "last inspection: ERROR " + last.error_code + ": " + last.message);
  } else {
    status.summary(Status::OK, std::string("last inspection: ") + statusName(last.status));
  }
  status.add("model", current ? current->id() : std::string());
  status.add("inspections", inspections);
  status.add("inspections cancelled", cancelled);
  status.add("scans received", received);
  status.add("scans dropped", dropped);
  if (inspections > 0) {
    status.add("last status", statusName(last.status));
    status.add("last registration", last.registration_status);
    status.add("last rmse [m]", last.rmse);
    status.add("last fitness", last.fitness);
    status.add("last scan points", last.counts.scan_points);
    status.add("last defects", last.defects.size());
    for (const auto& timing : last.timings) {
      status.add("time " + timing.stage + " [s]", timing.seconds);
    }
  }
}

ScanMessage InspectionNode::lastScan() const {
  std::lock_guard<std::mutex> lock(scan_mutex_);
  return last_scan_;
}

bool InspectionNode::stopping() const {
  std::lock_guard<std::mutex> lock(scan_mutex_);
  return stopping_;
}

std::string InspectionNode::installModel(const std::string& uri,
                                         const std::string& units,
                                         const std::string& id,
                                         ModelPlan plan,
                                         LoadModel::Response* summary) {
  const auto scale = fi::unitScale(units);
  if (!scale) {
    return "model units must be 'm', 'mm' or 'in' (got '" + units + "')";
  }
  const std::string path = resolveModelPath(uri);
  if (path.empty()) {
    return "cannot resolve model URL '" + uri + "'";
  }
  fi::ModelLoadResult loaded =
      fi::loadModel(path, *scale, id, config_.pipeline.descriptor, config_.model_cache_dir);
  for (const auto& warning : loaded.warnings) {
    ROS_WARN_STREAM(warning);
  }
  if (!loaded.status.ok()) {
    return loaded.status.message;
  }
  const std::shared_ptr<const fi::Model> model = loaded.model;
  {
    std::lock_guard<std::mutex> lock(model_mutex_);
    model_ = model;
    plan_ = std::move(plan);
    model_error_.clear();
  }
  const Eigen::Vector3d extent = model->bounds().extent();
  ROS_INFO_STREAM("loaded model '" << id << "' from " << path << ": " << model->mesh().faces.size()
                                   << " faces, extent " << extent.transpose() << " m");
  marker_pub_.publish(modelMarker(*model, config_.part_frame));
  if (summary != nullptr) {
    summary->vertices = static_cast<std::uint32_t>(model->mesh().vertices.size());
    summary->faces = static_cast<std::uint32_t>(model->mesh().faces.size());
    summary->extent = {extent.x(), extent.y(), extent.z()};
    summary->diagonal = extent.norm();
  }
  return "";
}

bool InspectionNode::onLoadModel(LoadModel::Request& request, LoadModel::Response& response) {
  const std::string id = request.model_id.empty() ? config_.model_id : request.model_id;
  // Anyone on the graph may call this: only files in the configured directories, capped.
  std::vector<std::string> dirs = config_.model_dirs;
  if (dirs.empty() && !config_.model.empty()) {
    dirs.push_back(std::filesystem::path(resolveModelPath(config_.model)).parent_path().string());
  }
  const std::string path = resolveModelPath(request.path);
  std::string error =
      path.empty()
          ? "cannot resolve model URL '" + request.path + "'"
          : checkModelAccess(
                path, dirs, static_cast<std::uintmax_t>(config_.max_model_mb) * 1024U * 1024U);
  // The regions and comparison points are the new model's: none unless the request names files
  // of them, which must lie where the model may.
  const auto planFile = [&](const std::string& uri, const std::string& what) {
    const std::string file = resolveModelPath(uri);
    if (file.empty()) {
      return std::make_pair(std::string(), "cannot resolve " + what + " URL '" + uri + "'");
    }
    return std::make_pair(
        file,
        checkModelAccess(
            file, dirs, static_cast<std::uintmax_t>(config_.max_model_mb) * 1024U * 1024U));
  };
  ModelPlan plan;
  if (error.empty() && !request.regions_uri.empty()) {
    const auto [regions_path, refused] = planFile(request.regions_uri, "regions");
    error = refused;
    if (error.empty()) {
      fi::RegionsLoadResult regions = fi::loadRegionsFile(regions_path);
      error = regions.status.message;
      plan.regions = std::move(regions.regions);
    }
  }
  if (error.empty() && !request.points_uri.empty()) {
    const auto [points_path, refused] = planFile(request.points_uri, "comparison points");
    error = refused;
    if (error.empty()) {
      fi::ComparisonPointsLoadResult points = fi::loadComparisonPointsFile(points_path);
      error = points.status.message;
      plan.comparison_points = std::move(points.points);
      plan.datum_precedence = std::move(points.datum_precedence);
    }
  }
  if (error.empty()) {
    error = installModel(request.path, request.units, id, std::move(plan), &response);
  }
  response.success = error.empty();
  response.message = error.empty() ? "loaded model '" + id + "'" : error;
  if (!error.empty()) {
    ROS_WARN_STREAM("~load_model refused: " << error);
  }
  return true;  // the outcome is in the response, never a failed call
}

std::optional<InspectionReport> InspectionNode::refusal(
    const Inspect::Request& request, const std::shared_ptr<const fi::Model>& model) const {
  if (!model) {
    std::lock_guard<std::mutex> lock(model_mutex_);
    return errorReport("MODEL_NOT_LOADED", model_error_);
  }
  if (!request.model_id.empty() && request.model_id != model->id()) {
    return errorReport(
        "UNKNOWN_MODEL",
        "model '" + request.model_id + "' is not loaded (loaded: '" + model->id() + "')");
  }
  return std::nullopt;
}

std::optional<InspectionReport> InspectionNode::requestedScan(const Inspect::Request& request,
                                                              ScanMessage* scan) const {
  if (request.use_last_scan) {
    *scan = lastScan();
    if (!*scan) {
      return errorReport("NO_SCAN",
                         "use_last_scan is set but no scan has arrived on '" +
                             scan_sub_.getTopic() + "' or '" + scan_mesh_sub_.getTopic() + "'");
    }
  } else if (hasCloud(request.mesh.cloud) || !request.mesh.polygons.empty()) {
    if (hasCloud(request.cloud)) {
      return errorReport("INVALID_INPUT",
                         "the request sets both cloud and mesh: give one scan per request");
    }
    if (auto refused = tooBig(request.mesh.cloud, request.mesh.header)) {
      return refused;
    }
    scan->mesh = boost::make_shared<const pcl_msgs::PolygonMesh>(request.mesh);
  } else {
    if (auto refused = tooBig(request.cloud, request.cloud.header)) {
      return refused;
    }
    scan->cloud = boost::make_shared<const sensor_msgs::PointCloud2>(request.cloud);
  }
  return std::nullopt;
}

std::optional<InspectionReport> InspectionNode::tooBig(const sensor_msgs::PointCloud2& cloud,
                                                       const std_msgs::Header& header) const {
  const std::uint64_t points = std::uint64_t{cloud.width} * cloud.height;
  const std::uint64_t max_points = config_.pipeline.input.max_points;
  if (points <= max_points) {
    return std::nullopt;
  }
  InspectionReport report =
      errorReport("INVALID_INPUT",
                  "scan has " + std::to_string(points) +
                      " points, more than input/max_points = " + std::to_string(max_points));
  report.header = header;
  return report;
}

std::optional<InspectionReport> InspectionNode::initialPose(
    const Inspect::Request& request,
    const std_msgs::Header& scan_header,
    std::optional<Eigen::Isometry3d>* pose) const {
  const geometry_msgs::TransformStamped& guess = request.initial_guess;
  const auto refused = [&scan_header](const std::string& code, const std::string& message) {
    InspectionReport report = errorReport(code, message);
    report.header = scan_header;
    return report;
  };
  if (request.alignment > Inspect::Request::ALIGN_FIXED) {
    return refused("INVALID_INPUT",
                   "alignment " + std::to_string(request.alignment) +
                       " is none of ALIGN_AUTO (0), ALIGN_ICP_ONLY (1), ALIGN_FIXED (2)");
  }
  if (guess.header.frame_id.empty()) {
    if (request.alignment != Inspect::Request::ALIGN_AUTO) {
      return refused(
          "INVALID_INPUT",
          std::string(request.alignment == Inspect::Request::ALIGN_FIXED ? "ALIGN_FIXED"
                                                                         : "ALIGN_ICP_ONLY") +
              " needs initial_guess (its header.frame_id is empty)");
    }
    return std::nullopt;  // search from scratch
  }
  if (!guess.child_frame_id.empty() && guess.child_frame_id != config_.part_frame) {
    return refused("INVALID_INPUT",
                   "initial_guess.child_frame_id is '" + guess.child_frame_id +
                       "': it must be the part frame '" + config_.part_frame + "' or empty");
  }
  const auto& q = guess.transform.rotation;
  const auto& t = guess.transform.translation;
  const double norm = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (!std::isfinite(norm + t.x + t.y + t.z) || std::abs(norm - 1.0) > 1e-3) {
    return refused("INVALID_INPUT",
                   "initial_guess's rotation must be a unit quaternion and its translation "
                   "finite (quaternion norm " +
                       std::to_string(norm) + ")");
  }
  // The part's pose in the guess's frame, carried into the scan's frame at the scan's stamp.
  Eigen::Isometry3d T_scan_guess = Eigen::Isometry3d::Identity();
  if (guess.header.frame_id != scan_header.frame_id) {
    try {
      T_scan_guess =
          tf2::transformToEigen(tf_buffer_.lookupTransform(scan_header.frame_id,
                                                           guess.header.frame_id,
                                                           scan_header.stamp,
                                                           ros::Duration(config_.tf_timeout)));
    } catch (const tf2::TransformException& error) {
      return refused("TF_ERROR",
                     "cannot move initial_guess from frame '" + guess.header.frame_id +
                         "' into the scan's frame '" + scan_header.frame_id + "' at stamp " +
                         std::to_string(scan_header.stamp.toSec()) + " within " +
                         std::to_string(config_.tf_timeout) + " s: " + error.what());
    }
  }
  const Eigen::Isometry3d T_scan_part = T_scan_guess * tf2::transformToEigen(guess);
  *pose = T_scan_part.inverse();  // scan → CAD: the CAD frame is the part frame
  return std::nullopt;
}

InspectionReport InspectionNode::inspect(const Inspect::Request& request,
                                         ScanMessage scan,
                                         const std::shared_ptr<const fi::Model>& model,
                                         const ModelPlan& plan,
                                         const StageHook& stage) {
  if (auto refused = refusal(request, model)) {
    return *refused;
  }
  std::string scan_name = "auto_inspect: topic '" + scan_sub_.getTopic() + "'";
  if (!scan) {
    if (auto refused = requestedScan(request, &scan)) {
      return *refused;
    }
    scan_name = request.use_last_scan ? "Inspect: last scan" : "Inspect request";
  }
  if (scan.mesh) {
    scan_name += " (mesh)";
  }
  const std_msgs::Header& scan_header = scan.header();
  // Before converting: a far too big cloud must not be copied again.
  if (auto refused = tooBig(scan.mesh ? scan.mesh->cloud : *scan.cloud, scan_header)) {
    return *refused;
  }
  if (!stage("converting", kConvertingProgress)) {
    return cancelledReport("before the scan was converted", scan_header);
  }
  const CloudConversion converted = scan.mesh ? meshToScan(*scan.mesh) : cloudToScan(*scan.cloud);
  if (!converted.status.ok()) {
    InspectionReport report =
        errorReport(errorCode(converted.status.code), converted.status.message);
    report.header = scan_header;
    return report;
  }
  std::optional<Eigen::Isometry3d> initial;
  if (auto refused = initialPose(request, scan_header, &initial)) {
    return *refused;
  }
  std_msgs::Header header = scan_header;
  // With a fixed frame the scan is inspected where it was measured (a range image keeps its
  // sensor at the origin, which orients its normals) and the pose is then carried into the
  // fixed frame at the scan's stamp.
  Eigen::Isometry3d T_fixed_scan = Eigen::Isometry3d::Identity();
  if (!config_.fixed_frame.empty() && header.frame_id != config_.fixed_frame) {
    try {
      T_fixed_scan = tf2::transformToEigen(tf_buffer_.lookupTransform(
          config_.fixed_frame, header.frame_id, header.stamp, ros::Duration(config_.tf_timeout)));
    } catch (const tf2::TransformException& error) {
      InspectionReport report = errorReport(
          "TF_ERROR",
          "cannot move the scan from frame '" + header.frame_id + "' into '" + config_.fixed_frame +
              "' at stamp " + std::to_string(header.stamp.toSec()) + " within " +
              std::to_string(config_.tf_timeout) + " s: " + error.what());
      report.header = scan_header;
      return report;
    }
    header.frame_id = config_.fixed_frame;
  }
  fi::PipelineConfig pipeline = requestPipeline(config_.pipeline, request);
  pipeline.regions = plan.regions;
  pipeline.comparison_points = plan.comparison_points;
  pipeline.datum_precedence = plan.datum_precedence;
  // ~input/crop_box is given in the fixed frame when there is one (a box around the fixture
  // holds wherever a robot carries the scanner), else in the scan's own.
  pipeline.input.crop_frame_from_scan = T_fixed_scan;
  if (!stage("inspecting", kInspectingProgress)) {
    return cancelledReport("before the inspection started", scan_header);
  }
  // The core's own stages, mapped into the inspecting span; a cancel stops it between stages.
  const auto core_stage = [&stage](const std::string& name, double fraction) {
    return stage(name,
                 kInspectingProgress + fraction * (kPublishingProgress - kInspectingProgress));
  };
  fi::InspectionResult result =
      !initial ? fi::inspect(*model, converted.scan, pipeline, core_stage)
      : request.alignment == Inspect::Request::ALIGN_FIXED
          ? fi::inspectAt(*model, converted.scan, *initial, pipeline, core_stage)
          : fi::inspectFrom(*model, converted.scan, *initial, pipeline, core_stage);
  // fixed → scan → CAD (unchanged without a fixed frame; a failed one stays the identity)
  if (result.registration != fi::RegistrationStatus::kFailed) {
    result.T_cad_scan = result.T_cad_scan * T_fixed_scan.inverse();
    for (auto& alternative : result.alternatives) {
      alternative = alternative * T_fixed_scan.inverse();
    }
    fi::DatumAlignment& datums = result.datum_alignment;
    datums.T_cad_scan_best_fit = datums.T_cad_scan_best_fit * T_fixed_scan.inverse();
    datums.T_cad_scan = datums.T_cad_scan * T_fixed_scan.inverse();
  }
  // The core's non-fatal findings (a pose ICP moved far from the guess, a coarse CAD's chord
  // error, ...) go to rosout; the report files hold them too.
  for (const std::string& warning : result.warnings) {
    ROS_WARN_STREAM("inspection: " << warning);
  }
  if (result.status.code == fi::StatusCode::kCancelled) {
    return cancelledReport("during stage 'inspecting' (" + result.status.message + ")",
                           scan_header);
  }
  if (!stage("publishing", kPublishingProgress)) {
    return cancelledReport("after stage 'inspecting', before publishing", scan_header);
  }
  InspectionReport report = toReport(result, header, config_.part_frame);
  report.tolerance_upper = pipeline.tolerance.upper;
  report.tolerance_lower = pipeline.tolerance.lower;
  report.part_id = request.part_id;  // names the report files
  archive(result, pipeline, *model, scan, scan_name, &report);
  publish(result,
          fi::toleranceBands(pipeline.regions, result.deviation_map.region, pipeline.tolerance),
          report);
  return report;
}

void InspectionNode::archive(const fi::InspectionResult& result,
                             const fi::PipelineConfig& pipeline,
                             const fi::Model& model,
                             const ScanMessage& scan,
                             const std::string& scan_name,
                             InspectionReport* report) const {
  if (config_.report_dir.empty()) {
    return;
  }
  ReportSource source;
  source.model_path = model.source();
  source.scan_name = scan_name;
  source.part_id = report->part_id;
  fi::ContentHash hash;
  const auto& data = scan.mesh ? scan.mesh->cloud.data : scan.cloud->data;
  hash.addBytes(data.data(), data.size());
  source.scan_hash = hash.hex();
  const ReportFilesResult written =
      writeReportFiles(config_.report_dir, result, pipeline, model, source, report->header);
  if (!written.error.empty()) {
    ROS_WARN_STREAM("report files: " << written.error);
  }
  report->report_files = written.files;
}

void InspectionNode::publish(const fi::InspectionResult& result,
                             const fi::ToleranceBands& tolerance,
                             const InspectionReport& report) {
  if (result.registration == fi::RegistrationStatus::kFailed) {
    return;  // no pose: nothing to place in the part frame
  }
  // A fixed pose goes on tf too, so the deviation cloud below is drawn where it was measured;
  // ~pose carries a registered pose's covariance, which a fixed one does not have.
  const bool fixed = result.registration == fi::RegistrationStatus::kFixed;
  if (result.registration == fi::RegistrationStatus::kOk || fixed) {
    if (config_.publish_tf) {
      if (config_.tf_static) {
        tf_static_broadcaster_.sendTransform(report.transform);
      } else {
        tf_broadcaster_.sendTransform(report.transform);
      }
    }
    if (!fixed) {
      pose_pub_.publish(poseWithCovariance(report));
    }
  }
  std_msgs::Header part_header = report.header;
  part_header.frame_id = config_.part_frame;
  // Published as shared pointers: subscribers in the same nodelet manager get them uncopied.
  if (deviation_pub_.getNumSubscribers() > 0) {
    deviation_pub_.publish(boost::make_shared<const sensor_msgs::PointCloud2>(
        deviationCloud(result, tolerance, part_header, 0)));
  }
  // Always: it is small (~viz_max_points) and latched for viewers that come later.
  deviation_viz_pub_.publish(boost::make_shared<const sensor_msgs::PointCloud2>(deviationCloud(
      result, tolerance, part_header, static_cast<std::size_t>(config_.viz_max_points))));
  defects_pub_.publish(defectMarkers(result, part_header));
}

InspectionReport InspectionNode::inspectAndPublish(const Inspect::Request& request,
                                                   const ScanMessage& scan) {
  std::lock_guard<std::timed_mutex> serial(inspect_mutex_);
  return inspectAndPublishLocked(
      request, [](const std::string&, double) { return true; }, scan);
}

InspectionReport InspectionNode::inspectAndPublishLocked(const Inspect::Request& request,
                                                         const StageHook& stage,
                                                         const ScanMessage& scan) {
  std::shared_ptr<const fi::Model> current;
  ModelPlan plan;
  {
    std::lock_guard<std::mutex> lock(model_mutex_);  // the model with its own plan
    current = model_;
    plan = plan_;
  }
  InspectionReport report = inspect(request, scan, current, plan, stage);
  report.part_id = request.part_id;
  report.model_id = current ? current->id() : "";
  if (report.error_code == kCancelledCode) {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++cancelled_;
    return report;
  }
  if (report.status == InspectionReport::ERROR) {
    ROS_WARN_STREAM("inspection " << report.error_code << ": " << report.message);
  }
  result_pub_.publish(report);
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++inspections_;
    last_report_ = report;
  }
  return report;
}

bool InspectionNode::onInspect(Inspect::Request& request, Inspect::Response& response) {
  const InspectionReport report = inspectAndPublish(request);
  response.status = report.status;
  response.message = report.message;
  response.report = report;
  return true;  // the outcome is in response.status, never a failed call
}

}  // namespace freeform_inspection_ros
