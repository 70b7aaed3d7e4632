// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// demo_client: the client of the one-command demo (scripts/demo, launch/demo.launch). Takes one
// scan of the virtual scanner with its ground truth, asks the inspection node to inspect it
// (~inspect with the cloud in the request), and prints the verdict, the pose error against the
// truth, the deviation statistics, the defects and the report files. Exits 0 when a verdict was
// given and the pose is within ~max_angle_deg and ~max_offset_ratio of the CAD diagonal of the
// truth, 1 otherwise. Parameters and their defaults: docs/ros.md (demo).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include "conversions.h"
#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/Marker.h>

#include <freeform_inspection/Inspect.h>

namespace freeform_inspection_ros {
namespace {

using freeform_inspection::Inspect;
using freeform_inspection::InspectionReport;

struct ClientConfig {
  std::string node = "freeform_inspection";  // the inspection node, resolved like a topic
  std::string part_id = "demo-blade-0001";
  double timeout = 180.0;  // [s] for each wait: scan, node, viewer
  double max_angle_deg = 0.5;
  double max_offset_ratio = 0.005;  // of the CAD's bounding-box diagonal
};

// Spins until `ready` holds; false on timeout or shutdown.
template <typename Ready>
bool spinUntil(const Ready& ready, double timeout) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::ok() && !ready()) {
    if (ros::WallTime::now() > end) {
      return false;
    }
    ros::spinOnce();
    ros::WallDuration(0.02).sleep();
  }
  return ros::ok();
}

// The CAD's bounding-box diagonal from its latched marker (triangle corners in metres).
double markerDiagonal(const visualization_msgs::Marker& marker) {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY);
  Eigen::Vector3d high = -low;
  for (const auto& p : marker.points) {
    const Eigen::Vector3d q(p.x, p.y, p.z);
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  return marker.points.empty() ? 0.0 : (high - low).norm();
}

std::string mm(double metres) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4f mm", metres * 1000.0);
  return text;
}

void printReport(const InspectionReport& report) {
  const auto& d = report.deviation;
  std::cout << "verdict:       " << statusName(report.status) << " (" << report.message << ")\n"
            << "registration:  " << report.registration_status << ", rmse " << mm(report.rmse)
            << ", fitness " << report.fitness << "\n"
            << "pose spread:   " << report.pose_rotation_std_deg << " deg, "
            << mm(report.pose_translation_std) << " (1 sigma, from the noise)\n";
  if (report.counts.support_points > 0) {
    std::cout << "support:       " << report.counts.support_points
              << " points of the table under the part removed before the registration\n";
  }
  std::cout << "tolerance:     " << mm(report.tolerance_lower) << " .. "
            << mm(report.tolerance_upper) << "\n"
            << "deviation:     mean " << mm(d.mean) << ", std " << mm(d.std) << ", p5 " << mm(d.p5)
            << ", p95 " << mm(d.p95) << ", min " << mm(d.min) << ", max " << mm(d.max) << "\n"
            << "               " << d.n_points << " points, " << 100.0 * d.in_tolerance_fraction
            << " % in tolerance, coverage " << 100.0 * d.coverage << " %\n"
            << "defects:       " << report.defects.size() << "\n";
  for (const auto& defect : report.defects) {
    std::cout << "  #" << defect.id << ": peak " << mm(defect.peak) << ", " << defect.points
              << " points, " << defect.area * 1e6 << " mm^2 at (" << mm(defect.centroid.x) << ", "
              << mm(defect.centroid.y) << ", " << mm(defect.centroid.z) << ") in the part\n";
  }
  double total = 0.0;
  for (const auto& timing : report.timings) {
    total += timing.seconds;
  }
  std::cout << "time:          " << total << " s in the pipeline\n";
  for (const auto& file : report.report_files) {
    std::cout << "written:       " << file << "\n";
  }
}

int run() {
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  ClientConfig config;
  pnh.param("node", config.node, config.node);
  pnh.param("part_id", config.part_id, config.part_id);
  pnh.param("timeout", config.timeout, config.timeout);
  pnh.param("max_angle_deg", config.max_angle_deg, config.max_angle_deg);
  pnh.param("max_offset_ratio", config.max_offset_ratio, config.max_offset_ratio);
  const std::string node = nh.resolveName(config.node);

  geometry_msgs::TransformStampedConstPtr truth;
  sensor_msgs::PointCloud2ConstPtr scan;
  visualization_msgs::MarkerConstPtr marker;
  // A scan and its truth carry the same stamp; they come on two connections, in either order.
  // The scan is subscribed first: the scanner starts once scan_truth has a subscriber.
  bool matched = false;
  auto scan_sub = nh.subscribe<sensor_msgs::PointCloud2>(
      "scan", 1, [&](const sensor_msgs::PointCloud2ConstPtr& message) {
        if (!matched) {
          scan = message;
        }
      });
  auto truth_sub = nh.subscribe<geometry_msgs::TransformStamped>(
      "scan_truth", 10, [&](const geometry_msgs::TransformStampedConstPtr& message) {
        if (!matched) {
          truth = message;
        }
      });
  auto marker_sub = nh.subscribe<visualization_msgs::Marker>(
      node + "/model_marker", 1, [&](const visualization_msgs::MarkerConstPtr& message) {
        marker = message;
      });
  std::cout << "waiting for the inspection node '" << node << "' and a scan ..." << std::endl;
  if (!ros::service::waitForService(node + "/inspect", ros::Duration(config.timeout))) {
    std::cerr << "demo_client: no service " << node << "/inspect after " << config.timeout << " s"
              << std::endl;
    return 1;
  }
  if (!spinUntil(
          [&] {
            matched = scan && truth && scan->header.stamp == truth->header.stamp;
            return matched && marker;
          },
          config.timeout)) {
    std::cerr << "demo_client: no scan with its truth on '" << scan_sub.getTopic() << "' / '"
              << truth_sub.getTopic() << "', or no CAD marker, after " << config.timeout << " s"
              << std::endl;
    return 1;
  }
  std::cout << "scan: " << scan->width * scan->height << " points in frame '"
            << scan->header.frame_id << "'; calling " << node << "/inspect" << std::endl;
  Inspect inspect;
  inspect.request.part_id = config.part_id;
  inspect.request.cloud = *scan;
  inspect.request.tolerance_upper = NAN;
  inspect.request.tolerance_lower = NAN;
  if (!ros::service::call(node + "/inspect", inspect)) {
    std::cerr << "demo_client: the call to " << node << "/inspect failed" << std::endl;
    return 1;
  }
  const InspectionReport& report = inspect.response.report;
  printReport(report);
  if (report.status != InspectionReport::PASS && report.status != InspectionReport::FAIL) {
    std::cerr << "demo_client: no verdict: " << report.message << std::endl;
    return 1;
  }
  // Both are the part pose in the scan frame.
  const Eigen::Isometry3d found = tf2::transformToEigen(report.transform);
  const Eigen::Isometry3d expected = tf2::transformToEigen(*truth);
  const double angle =
      Eigen::AngleAxisd(found.linear().transpose() * expected.linear()).angle() * 180.0 / M_PI;
  const double offset = (found.translation() - expected.translation()).norm();
  const double diagonal = markerDiagonal(*marker);
  std::cout << "pose error:    " << angle << " deg, " << mm(offset) << " ("
            << 100.0 * offset / diagonal << " % of the CAD diagonal " << mm(diagonal) << ")"
            << std::endl;
  if (angle > config.max_angle_deg || offset > config.max_offset_ratio * diagonal) {
    std::cerr << "demo_client: pose error above " << config.max_angle_deg << " deg / "
              << 100.0 * config.max_offset_ratio << " % of the diagonal" << std::endl;
    return 1;
  }
  return 0;
}

}  // namespace
}  // namespace freeform_inspection_ros

int main(int argc, char** argv) {
  ros::init(argc, argv, "demo_client");
  return freeform_inspection_ros::run();
}
