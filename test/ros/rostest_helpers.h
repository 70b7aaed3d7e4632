// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <functional>
#include <optional>
#include <string>

#include <Eigen/Geometry>
#include <ros/duration.h>
#include <ros/time.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>

#include "freeform_inspection/types.h"
#include <freeform_inspection/Inspect.h>

/// What the rostest clients share: the node's name, the sample scan and its truth, waiting.
namespace freeform_inspection_rostest {

/// Generous: the node loads the model before it advertises anything.
const ros::Duration kWait(30.0);
/// Upper bound for one inspection of the sample scan on a loaded 2-core machine.
const ros::Duration kInspectWait(90.0);
/// The sample scan's pose tolerance (the brief's 0.5° / 0.5 mm; ICP reaches far better).
constexpr double kPoseToleranceDeg = 0.5;
constexpr double kPoseToleranceM = 0.0005;

/// tf buffer filled by a listener started in main(); null before.
extern tf2_ros::Buffer* tf_buffer;

/// @brief The test's private parameter `~name`; a missing one fails the test.
std::string param(const std::string& name);

/// @brief Resolved name of the node under test: `~node`, default "/freeform_inspection".
std::string nodeName();

/// @brief An unorganized FLOAT32 xyz cloud in `frame`, stamped 1234.5 s.
sensor_msgs::PointCloud2 toCloud(const freeform_inspection::Points& points,
                                 const std::string& frame);

/// @brief The sample scan (`~sample_scan`, metres) as a cloud in frame "scanner".
sensor_msgs::PointCloud2 sampleCloud();

/// @brief T_cad_scan of the sample scan (`~sample_truth`, 4 × 4 row-major, as generate_blade
/// wrote it).
Eigen::Isometry3d sampleTruth();

/// @brief Rotation angle between two poses [deg].
double angleDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

/// @brief Expects `part_in_scan` (the part pose in the scan frame) to be inverse(T_cad_scan) of
/// the sample within kPoseToleranceDeg / kPoseToleranceM; `what` names it in failures.
void expectSamplePose(const Eigen::Isometry3d& part_in_scan, const std::string& what);

/// @brief The part pose on tf (parent "scanner", child "part") at `stamp`, waiting up to 5 s for
/// it; nothing if it does not arrive.
std::optional<Eigen::Isometry3d> partOnTf(const ros::Time& stamp);

/// @brief An Inspect request for `cloud` with the configured tolerances (NaN) and `part_id`.
freeform_inspection::Inspect::Request cloudRequest(const sensor_msgs::PointCloud2& cloud,
                                                   const std::string& part_id = "sn-0001");

/// @brief Calls the node's `~inspect` (waiting for it up to kWait); a failed call fails the test.
freeform_inspection::Inspect::Response callInspect(freeform_inspection::Inspect::Request request);

/// @brief Polls `done` every 20 ms until it holds or `timeout` (wall time) passes.
/// @return whether it held.
bool waitUntil(const std::function<bool()>& done, const ros::Duration& timeout);

}  // namespace freeform_inspection_rostest
