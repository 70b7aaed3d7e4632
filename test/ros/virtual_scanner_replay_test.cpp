// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// rostest client of virtual_scanner_replay.test and bag_replay.test: scans from the virtual
// scanner (live, or played from data/blade/blade_scans.bag) reach the inspection node with
// auto_inspect; every ~result is matched to the `scan_truth` with the same stamp. Each registers
// within 0.5° and 0.5 % of the CAD diagonal, clean scans pass, and the scan with the injected
// dent fails with a missing-material defect on the dent. Scans in ~skip_scans (views the
// pipeline cannot register) must still be reported, and may be refused, but not with a wrong
// pose reported ok.
#include <algorithm>
#include <iostream>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "rostest_helpers.h"
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2_eigen/tf2_eigen.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/model.h"
#include <freeform_inspection/InspectionReport.h>

namespace {

using freeform_inspection::InspectionReport;
using geometry_msgs::TransformStamped;
using namespace freeform_inspection_rostest;  // NOLINT(google-build-using-namespace): test helpers

constexpr double kAngleToleranceDeg = 0.5;
constexpr double kTranslationShareOfDiagonal = 0.005;

// Every message on a topic, in arrival order.
template <typename Message>
class All {
 public:
  explicit All(const std::string& topic) {
    subscriber_ =
        nh_.subscribe<Message>(topic, 20, [this](const boost::shared_ptr<const Message>& message) {
          std::lock_guard<std::mutex> lock(mutex_);
          messages_.push_back(*message);
        });
  }
  std::vector<Message> get() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_;
  }

 private:
  ros::NodeHandle nh_;
  mutable std::mutex mutex_;
  std::vector<Message> messages_;
  ros::Subscriber subscriber_;
};

template <typename T>
T privateParam(const std::string& name) {
  T value{};
  EXPECT_TRUE(ros::param::get("~" + name, value)) << "missing test parameter ~" << name;
  return value;
}

// The CAD's bounding-box diagonal [m] (the pipeline's L).
double cadDiagonal() {
  const auto scale = freeform_inspection::unitScale(param("model_units"));
  EXPECT_TRUE(scale);
  const auto loaded = freeform_inspection::loadMesh(param("model_path"), scale ? *scale : 1.0);
  EXPECT_TRUE(loaded.status.ok()) << loaded.status.message;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300);
  Eigen::Vector3d high = -low;
  for (const Eigen::Vector3d& v : loaded.mesh.vertices) {
    low = low.cwiseMin(v);
    high = high.cwiseMax(v);
  }
  return (high - low).norm();
}

TEST(ScanReplay, EveryScanRegistersAndTheDentIsFound) {
  const int scans = privateParam<int>("scans");
  const int dent_scan = privateParam<int>("dent_scan");
  const std::vector<double> dent = privateParam<std::vector<double>>("dent");
  std::vector<int> skip;
  ros::param::get("~skip_scans", skip);
  ASSERT_EQ(dent.size(), 5U) << "~dent is [x, y, z, radius, depth]";
  const double diagonal = cadDiagonal();
  ASSERT_GT(diagonal, 0.0);

  All<TransformStamped> truths("scan_truth");
  All<InspectionReport> results(nodeName() + "/result");
  // The node drops nothing at the scanner's rate, so every scan gets a report.
  const auto all_reported = [&] {
    const auto truth = truths.get();
    const auto reports = results.get();
    return static_cast<int>(truth.size()) >= scans &&
           std::all_of(truth.begin(), truth.end(), [&](const TransformStamped& t) {
             return std::any_of(reports.begin(), reports.end(), [&](const InspectionReport& r) {
               return r.header.stamp == t.header.stamp;
             });
           });
  };
  ASSERT_TRUE(waitUntil(all_reported, kWait + ros::Duration(scans * kInspectWait.toSec())))
      << truths.get().size() << " truths and " << results.get().size() << " reports arrived, "
      << scans << " scans expected";

  const auto truth = truths.get();
  const auto reports = results.get();
  ASSERT_EQ(static_cast<int>(truth.size()), scans);
  const Eigen::Vector3d dent_centre(dent[0], dent[1], dent[2]);
  for (int i = 0; i < scans; ++i) {
    const TransformStamped& expected = truth[static_cast<std::size_t>(i)];
    const auto report =
        std::find_if(reports.begin(), reports.end(), [&](const InspectionReport& r) {
          return r.header.stamp == expected.header.stamp;
        });
    ASSERT_NE(report, reports.end());
    const std::string what = "scan " + std::to_string(i) + " (stamp " +
                             std::to_string(expected.header.stamp.toSec()) + ")";
    EXPECT_EQ(report->header.frame_id, expected.header.frame_id) << what;
    const Eigen::Isometry3d estimated = tf2::transformToEigen(report->transform);
    const Eigen::Isometry3d true_pose = tf2::transformToEigen(expected);
    const double angle = angleDeg(estimated, true_pose);
    const double offset = (estimated.translation() - true_pose.translation()).norm();
    if (std::find(skip.begin(), skip.end(), i) != skip.end()) {
      // An unregistrable view: it may be refused, but a pose reported ok must be right.
      std::cout << what << ": skipped (~skip_scans), registration " << report->registration_status
                << ": " << report->message << "\n";
      if (report->registration_status == "ok") {
        EXPECT_LT(angle, kAngleToleranceDeg) << what;
        EXPECT_LT(offset, kTranslationShareOfDiagonal * diagonal) << what;
      } else {
        EXPECT_EQ(report->status, InspectionReport::NOT_EVALUATED) << what;
      }
      continue;
    }
    EXPECT_EQ(report->registration_status, "ok") << what << ": " << report->message;
    EXPECT_LT(angle, kAngleToleranceDeg) << what;
    EXPECT_LT(offset, kTranslationShareOfDiagonal * diagonal) << what;
    // The pose's covariance arrives filled: symmetric, positive variances, the stated spreads.
    for (int r = 0; r < 6; ++r) {
      EXPECT_GT(report->pose_covariance[static_cast<std::size_t>(7 * r)], 0.0) << what;
      for (int c = 0; c < 6; ++c) {
        EXPECT_EQ(report->pose_covariance[static_cast<std::size_t>(6 * r + c)],
                  report->pose_covariance[static_cast<std::size_t>(6 * c + r)])
            << what;
      }
    }
    EXPECT_GT(report->pose_rotation_std_deg, 0.0) << what;
    EXPECT_LT(report->pose_rotation_std_deg, kAngleToleranceDeg) << what;
    EXPECT_GT(report->pose_translation_std, 0.0) << what;
    EXPECT_LT(report->pose_translation_std, kTranslationShareOfDiagonal * diagonal) << what;
    std::cout << what << ": " << report->counts.scan_points << " points, registration "
              << report->registration_status << ", rotation error " << angle
              << " deg, translation error " << offset * 1e3 << " mm (" << 100.0 * offset / diagonal
              << " % of L), rmse " << report->rmse * 1e3 << " mm, pose spread "
              << report->pose_rotation_std_deg << " deg / " << report->pose_translation_std * 1e3
              << " mm, status " << int{report->status} << ", " << report->defects.size()
              << " defect(s)\n";
    if (i != dent_scan) {
      EXPECT_EQ(report->status, InspectionReport::PASS) << what << ": " << report->message;
      continue;
    }
    EXPECT_EQ(report->status, InspectionReport::FAIL) << what << ": " << report->message;
    bool found = false;
    for (const auto& defect : report->defects) {
      const Eigen::Vector3d centroid(defect.centroid.x, defect.centroid.y, defect.centroid.z);
      const double distance = (centroid - dent_centre).norm();
      std::cout << what << ": defect " << defect.id << " sign " << int{defect.sign} << ", "
                << defect.points << " points, peak " << defect.peak * 1e3 << " mm, "
                << distance * 1e3 << " mm from the dent centre\n";
      found = found || (defect.sign == -1 && distance < dent[3] && defect.peak < 0.5 * dent[4]);
    }
    EXPECT_TRUE(found) << what << ": no missing-material defect within " << dent[3] * 1e3
                       << " mm of the dent with a peak below " << 0.5 * dent[4] * 1e3 << " mm";
  }
}

}  // namespace
