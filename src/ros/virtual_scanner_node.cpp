// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// virtual_scanner_node: a simulated structured-light camera for the inspection node. Loads a
// CAD, scans it with makeVirtualScan (virtual_scanner.h) and publishes each scan as an organized
// PointCloud2 on `scan`, with its ground truth on tf and on `scan_truth`. Scan i (from 0) uses
// seed `~seed` + i. Parameters and topics: docs/virtual_scanner.md.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "conversions.h"
#include "parameters.h"
#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/transform_broadcaster.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/virtual_scanner.h"

namespace freeform_inspection_ros {
namespace {

namespace fi = freeform_inspection;

/// Everything read from the private parameters.
struct ScannerNodeConfig {
  std::string model;
  std::string model_units;
  std::string frame_id = "scanner";
  std::string truth_frame = "part_truth";
  double rate = 1.0;
  int count = 0;  // 0 = until shut down
  int seed = 1;
  int wait_for_subscribers = 0;
  std::vector<int> defect_scans;  // empty = every scan
  std::optional<Eigen::Isometry3d> pose;
  fi::VirtualScannerConfig scanner;
};

double toDouble(XmlRpc::XmlRpcValue& value, bool* ok) {
  if (value.getType() == XmlRpc::XmlRpcValue::TypeDouble) {
    return static_cast<double>(value);
  }
  if (value.getType() == XmlRpc::XmlRpcValue::TypeInt) {
    return static_cast<int>(value);
  }
  *ok = false;
  return 0.0;
}

// ~defects: a list of [x, y, z, radius, depth] in the CAD frame [m].
void readDefects(const ros::NodeHandle& pnh,
                 ScannerNodeConfig* config,
                 std::vector<std::string>* errors) {
  XmlRpc::XmlRpcValue list;
  if (!pnh.getParam("defects", list)) {
    return;
  }
  if (list.getType() != XmlRpc::XmlRpcValue::TypeArray) {
    errors->push_back("~defects must be a list of [x, y, z, radius, depth]");
    return;
  }
  for (int i = 0; i < list.size(); ++i) {
    XmlRpc::XmlRpcValue& item = list[i];
    bool ok = item.getType() == XmlRpc::XmlRpcValue::TypeArray && item.size() == 5;
    double values[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
    for (int k = 0; ok && k < 5; ++k) {
      values[k] = toDouble(item[k], &ok);
    }
    if (!ok) {
      errors->push_back("~defects[" + std::to_string(i) +
                        "] must be five numbers [x, y, z, radius, depth] (metres, CAD frame)");
      continue;
    }
    fi::SurfaceDefect defect;
    defect.centre = Eigen::Vector3d(values[0], values[1], values[2]);
    defect.radius = values[3];
    defect.depth = values[4];
    config->scanner.defects.push_back(defect);
  }
}

// ~pose: [x, y, z, qx, qy, qz, qw], the part in the scanner frame (with ~random_pose false).
void readPose(const ros::NodeHandle& pnh,
              ScannerNodeConfig* config,
              std::vector<std::string>* errors) {
  std::vector<double> pose;
  if (!pnh.getParam("pose", pose)) {
    return;
  }
  const Eigen::Quaterniond q = pose.size() == 7
                                   ? Eigen::Quaterniond(pose[6], pose[3], pose[4], pose[5])
                                   : Eigen::Quaterniond::Identity();
  if (pose.size() != 7 || !(q.norm() > 0.5)) {
    errors->push_back("~pose must be [x, y, z, qx, qy, qz, qw] with a unit quaternion");
    return;
  }
  Eigen::Isometry3d value = Eigen::Isometry3d::Identity();
  value.linear() = q.normalized().toRotationMatrix();
  value.translation() = Eigen::Vector3d(pose[0], pose[1], pose[2]);
  config->pose = value;
}

ScannerNodeConfig loadConfig(const ros::NodeHandle& pnh, std::vector<std::string>* errors) {
  ScannerNodeConfig config;
  fi::VirtualScannerConfig& scanner = config.scanner;
  scanner.width = 320;
  scanner.height = 240;
  pnh.param("model", config.model, config.model);
  pnh.param("model_units", config.model_units, config.model_units);
  pnh.param("frame_id", config.frame_id, config.frame_id);
  pnh.param("truth_frame", config.truth_frame, config.truth_frame);
  pnh.param("rate", config.rate, config.rate);
  pnh.param("count", config.count, config.count);
  pnh.param("seed", config.seed, config.seed);
  pnh.param("wait_for_subscribers", config.wait_for_subscribers, config.wait_for_subscribers);
  pnh.param("defect_scans", config.defect_scans, config.defect_scans);
  pnh.param("random_pose", scanner.random_pose, scanner.random_pose);
  pnh.param("width", scanner.width, scanner.width);
  pnh.param("height", scanner.height, scanner.height);
  pnh.param("fov_deg", scanner.horizontal_fov_deg, scanner.horizontal_fov_deg);
  pnh.param("fill_ratio", scanner.fill_ratio, scanner.fill_ratio);
  pnh.param("noise_ratio", scanner.noise_ratio, scanner.noise_ratio);
  pnh.param("dropout", scanner.dropout_probability, scanner.dropout_probability);
  pnh.param("support", scanner.support, scanner.support);
  readDefects(pnh, &config, errors);
  readPose(pnh, &config, errors);
  if (config.model.empty()) {
    errors->push_back("~model is required (CAD file path, file:// or package:// URL)");
  }
  if (!fi::unitScale(config.model_units)) {
    errors->push_back("~model_units must be 'm', 'mm' or 'in' (got '" + config.model_units +
                      "'): CAD units are never guessed");
  }
  if (config.frame_id.empty() || config.truth_frame.empty()) {
    errors->push_back("~frame_id and ~truth_frame must not be empty");
  }
  if (!(config.rate > 0.0)) {
    errors->push_back("~rate must be positive (got " + std::to_string(config.rate) + ")");
  }
  if (config.count < 0 || config.seed < 0 || config.wait_for_subscribers < 0) {
    errors->push_back("~count, ~seed and ~wait_for_subscribers must not be negative");
  }
  if (config.pose && scanner.random_pose) {
    errors->push_back("~pose needs ~random_pose false");
  }
  for (const std::string& problem : fi::validate(scanner)) {
    errors->push_back(problem);
  }
  return config;
}

bool appliesDefects(const ScannerNodeConfig& config, int index) {
  if (config.defect_scans.empty()) {
    return true;
  }
  for (const int scan : config.defect_scans) {
    if (scan == index) {
      return true;
    }
  }
  return false;
}

// Waits (wall time, polling) until `scan` and `scan_truth` have `wanted` subscribers each.
bool waitForSubscribers(const ros::Publisher& scan, const ros::Publisher& truth, int wanted) {
  if (wanted <= 0) {
    return true;
  }
  ROS_INFO_STREAM("waiting for " << wanted << " subscriber(s) on " << scan.getTopic() << " and "
                                 << truth.getTopic());
  while (ros::ok() && (static_cast<int>(scan.getNumSubscribers()) < wanted ||
                       static_cast<int>(truth.getNumSubscribers()) < wanted)) {
    ros::WallDuration(0.05).sleep();
  }
  // The connections count once the subscriber has them; give tf listeners a moment as well.
  ros::WallDuration(0.5).sleep();
  return ros::ok();
}

int run() {
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  std::vector<std::string> errors;
  ScannerNodeConfig config = loadConfig(pnh, &errors);
  for (const std::string& error : errors) {
    ROS_FATAL_STREAM("invalid parameter: " << error);
  }
  if (!errors.empty()) {
    return 1;
  }
  const std::string path = resolveModelPath(config.model);
  const fi::MeshLoadResult loaded = fi::loadMesh(path, *fi::unitScale(config.model_units));
  if (!loaded.status.ok()) {
    ROS_FATAL_STREAM("cannot load ~model '" << config.model << "': " << loaded.status.message);
    return 1;
  }
  const fi::MeshQuery cad(loaded.mesh);
  if (!cad.status().ok()) {
    ROS_FATAL_STREAM("unusable ~model '" << config.model << "': " << cad.status().message);
    return 1;
  }
  // Defect centres onto the surface, as virtual_scan does: the cap is measured from its centre.
  for (fi::SurfaceDefect& defect : config.scanner.defects) {
    const fi::ClosestPoint closest = cad.closest(defect.centre);
    if (closest.found) {
      defect.centre = closest.point;
    }
  }
  const std::vector<fi::SurfaceDefect> defects = config.scanner.defects;
  if (!config.scanner.random_pose && !config.pose) {
    // A fixed pose without ~pose: the one drawn from ~seed, for every scan.
    fi::VirtualScannerConfig first = config.scanner;
    first.random_pose = true;
    first.seed = static_cast<std::uint64_t>(config.seed);
    const fi::VirtualScan made = fi::makeVirtualScan(cad, first);
    config.pose = made.T_cad_scan.inverse();
  }
  if (config.pose) {
    config.scanner.T_sensor_cad = *config.pose;
  }

  ros::Publisher scan_pub = nh.advertise<sensor_msgs::PointCloud2>("scan", 3);
  ros::Publisher truth_pub = nh.advertise<geometry_msgs::TransformStamped>("scan_truth", 10);
  tf2_ros::TransformBroadcaster broadcaster;
  if (!waitForSubscribers(scan_pub, truth_pub, config.wait_for_subscribers)) {
    return 0;
  }
  ros::Rate rate(config.rate);
  for (int index = 0; ros::ok() && (config.count == 0 || index < config.count); ++index) {
    fi::VirtualScannerConfig scanner = config.scanner;
    scanner.seed = static_cast<std::uint64_t>(config.seed) + static_cast<std::uint64_t>(index);
    scanner.defects = appliesDefects(config, index) ? defects : std::vector<fi::SurfaceDefect>{};
    const fi::VirtualScan made = fi::makeVirtualScan(cad, scanner);
    for (const std::string& warning : made.warnings) {
      ROS_WARN_STREAM("scan " << index << ": " << warning);
    }
    if (!made.status.ok()) {
      ROS_ERROR_STREAM("scan " << index << " (seed " << scanner.seed
                               << ") not published: " << made.status.message);
    } else {
      std_msgs::Header header;
      header.stamp = ros::Time::now();
      header.frame_id = config.frame_id;
      header.seq = static_cast<std::uint32_t>(index);
      geometry_msgs::TransformStamped truth = tf2::eigenToTransform(made.T_cad_scan.inverse());
      truth.header = header;
      truth.child_frame_id = config.truth_frame;
      // Truth first: a subscriber matching reports to truths by stamp has it before the result.
      truth_pub.publish(truth);
      broadcaster.sendTransform(truth);
      scan_pub.publish(scanToCloud(made.scan, header));
      ROS_INFO_STREAM("scan " << index << " (seed " << scanner.seed << ", stamp " << header.stamp
                              << "): " << made.counts.valid << " points, " << made.counts.displaced
                              << " on defects");
    }
    if (config.count == 0 || index + 1 < config.count) {
      rate.sleep();
    }
  }
  // Let the last messages leave before the node ends.
  ros::WallDuration(1.0).sleep();
  return 0;
}

}  // namespace
}  // namespace freeform_inspection_ros

int main(int argc, char** argv) {
  ros::init(argc, argv, "virtual_scanner");
  return freeform_inspection_ros::run();
}
