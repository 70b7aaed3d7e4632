// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// rostest client of auto_inspect:=true: a scan published on `scan` is inspected without a call;
// the verdict and pose arrive on ~result and tf, the node's status on /diagnostics.
#include <mutex>
#include <string>

#include "rostest_helpers.h"
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_eigen/tf2_eigen.h>

#include <freeform_inspection/InspectionReport.h>

namespace {

using diagnostic_msgs::DiagnosticArray;
using diagnostic_msgs::DiagnosticStatus;
using freeform_inspection::InspectionReport;
using namespace freeform_inspection_rostest;  // NOLINT(google-build-using-namespace): test helpers

// The latest message on a topic, kept from the subscription's callback thread.
template <typename Message>
class Latest {
 public:
  explicit Latest(const std::string& topic) {
    subscriber_ =
        nh_.subscribe<Message>(topic, 10, [this](const boost::shared_ptr<const Message>& message) {
          std::lock_guard<std::mutex> lock(mutex_);
          message_ = message;
        });
  }
  boost::shared_ptr<const Message> get() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return message_;
  }

 private:
  ros::NodeHandle nh_;
  mutable std::mutex mutex_;
  boost::shared_ptr<const Message> message_;
  ros::Subscriber subscriber_;
};

// The node's own entry ("<node>: inspection") in a diagnostics array, or nullptr.
const DiagnosticStatus* nodeStatus(const DiagnosticArray& array) {
  const std::string name = nodeName().substr(1) + ": inspection";
  for (const auto& status : array.status) {
    if (status.name == name) {
      return &status;
    }
  }
  return nullptr;
}

std::string value(const DiagnosticStatus& status, const std::string& key) {
  for (const auto& entry : status.values) {
    if (entry.key == key) {
      return entry.value;
    }
  }
  return "";
}

TEST(AutoInspect, APublishedScanIsInspectedReportedAndDiagnosed) {
  Latest<InspectionReport> result(nodeName() + "/result");
  Latest<DiagnosticArray> diagnostics("/diagnostics");
  Latest<geometry_msgs::PoseWithCovarianceStamped> pose(nodeName() + "/pose");
  ros::NodeHandle nh;
  // Latched: the node receives the scan whenever its subscription connects.
  ros::Publisher scan = nh.advertise<sensor_msgs::PointCloud2>(param("scan_topic"), 1, true);
  scan.publish(sampleCloud());

  ASSERT_TRUE(waitUntil([&] { return result.get() != nullptr; }, kWait + kInspectWait))
      << "no report on " << nodeName() << "/result after publishing on " << scan.getTopic();
  const auto report = result.get();
  EXPECT_EQ(report->status, InspectionReport::PASS) << report->message;
  EXPECT_EQ(report->registration_status, "ok") << report->message;
  EXPECT_EQ(report->header.frame_id, "scanner");
  EXPECT_EQ(report->header.stamp, ros::Time(1234.5));
  expectSamplePose(tf2::transformToEigen(report->transform), "~result transform");
  // The regions of ~regions_file (data/blade/blade_regions.yaml): the tip left out, the root
  // judged in its own band.
  ASSERT_EQ(report->regions.size(), 2u);
  EXPECT_EQ(report->regions[0].name, "tip");
  EXPECT_EQ(report->regions[0].status, InspectionReport::NOT_EVALUATED);
  EXPECT_EQ(report->regions[1].name, "root");
  EXPECT_EQ(report->regions[1].status, InspectionReport::PASS) << report->regions[1].message;
  EXPECT_EQ(report->regions[1].tolerance_upper, 0.0005);
  EXPECT_GT(report->deviation.n_excluded, 0u);
  // The comparison points of ~points_file (data/blade/blade_points.yaml), each read and passed.
  ASSERT_EQ(report->comparison_points.size(), 3u);
  EXPECT_EQ(report->comparison_points[1].name, "span_50");
  EXPECT_EQ(report->comparison_points[1].tolerance_upper, 0.00005);
  for (const auto& point : report->comparison_points) {
    EXPECT_EQ(point.status, InspectionReport::PASS) << point.name << ": " << point.message;
    EXPECT_GE(point.points, 3u) << point.name;
  }
  const auto on_tf = partOnTf(ros::Time(1234.5));
  ASSERT_TRUE(on_tf);
  expectSamplePose(*on_tf, "tf scanner → part");

  // The same pose with its covariance on ~pose, for consumers that weigh it (a localizer).
  ASSERT_TRUE(waitUntil([&] { return pose.get() != nullptr; }, kWait))
      << "no pose on " << nodeName() << "/pose";
  const auto with_covariance = pose.get();
  EXPECT_EQ(with_covariance->header.frame_id, "scanner");
  EXPECT_EQ(with_covariance->header.stamp, ros::Time(1234.5));
  Eigen::Isometry3d published = Eigen::Isometry3d::Identity();
  tf2::fromMsg(with_covariance->pose.pose, published);
  expectSamplePose(published, "~pose");
  EXPECT_EQ(with_covariance->pose.covariance, report->pose_covariance);
  // Variances of a 30k-point scan at σ ≈ 20 µm: positive, and far below the tolerance's square.
  for (int i = 0; i < 6; ++i) {
    const double variance = with_covariance->pose.covariance[static_cast<std::size_t>(7 * i)];
    EXPECT_GT(variance, 0.0) << "variance " << i;
    EXPECT_LT(variance, 1e-8) << "variance " << i;  // (0.1 mm)² or (0.0057°)²
  }

  // Diagnostics update once a second; wait for the entry that has seen the inspection.
  const auto inspected = [&] {
    const auto array = diagnostics.get();
    const DiagnosticStatus* status = array ? nodeStatus(*array) : nullptr;
    return status != nullptr && value(*status, "inspections") == "1";
  };
  ASSERT_TRUE(waitUntil(inspected, ros::Duration(10.0)))
      << "no /diagnostics entry '" << nodeName().substr(1) << ": inspection' counting one";
  const auto array = diagnostics.get();  // the status is inside this message
  ASSERT_TRUE(array && nodeStatus(*array));
  const DiagnosticStatus& status = *nodeStatus(*array);
  EXPECT_EQ(status.level, DiagnosticStatus::OK);
  EXPECT_EQ(status.message, "last inspection: PASS");
  EXPECT_EQ(status.hardware_id, "freeform_inspection");
  EXPECT_EQ(value(status, "last status"), "PASS");
  EXPECT_EQ(value(status, "scans received"), "1");
  EXPECT_EQ(value(status, "scans dropped"), "0");
  EXPECT_EQ(value(status, "model"), "default");
}

}  // namespace
