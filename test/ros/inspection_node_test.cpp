// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// rostest client: the node starts with the shipped blade, publishes the CAD marker, answers
// Inspect with a status for every kind of request and keeps serving after bad ones.
#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "analytic_clouds.h"
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/Marker.h>

#include "freeform_inspection/io.h"
#include <freeform_inspection/Inspect.h>
#include <freeform_inspection/InspectionReport.h>
#include <freeform_inspection/LoadModel.h>

namespace {

using freeform_inspection::Inspect;
using freeform_inspection::InspectionReport;
using freeform_inspection::LoadModel;

const ros::Duration kWait(30.0);  // generous: the node loads the model before advertising
const std::string kNode = "/freeform_inspection";

std::string param(const std::string& name) {
  std::string value;
  EXPECT_TRUE(ros::param::get("~" + name, value)) << "missing test parameter ~" << name;
  return value;
}

sensor_msgs::PointCloud2 toCloud(const freeform_inspection::Points& points,
                                 const std::string& frame) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header.frame_id = frame;
  cloud.header.stamp = ros::Time(1234.5);
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  modifier.setPointCloud2FieldsByString(1, "xyz");
  modifier.resize(points.size());
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x");
  for (const auto& p : points) {
    x[0] = static_cast<float>(p.x());
    x[1] = static_cast<float>(p.y());
    x[2] = static_cast<float>(p.z());
    ++x;
  }
  return cloud;
}

Inspect::Response callInspect(Inspect::Request request) {
  Inspect srv;
  srv.request = std::move(request);
  EXPECT_TRUE(ros::service::waitForService(kNode + "/inspect", kWait));
  EXPECT_TRUE(ros::service::call(kNode + "/inspect", srv)) << "the call itself must never fail";
  return srv.response;
}

Inspect::Request cloudRequest(const sensor_msgs::PointCloud2& cloud) {
  Inspect::Request request;
  request.use_last_scan = false;
  request.cloud = cloud;
  request.part_id = "sn-0001";
  request.tolerance_upper = std::numeric_limits<double>::quiet_NaN();
  request.tolerance_lower = std::numeric_limits<double>::quiet_NaN();
  return request;
}

TEST(InspectionNode, PublishesLatchedCadMarkerInMetresInPartFrame) {
  const auto marker =
      ros::topic::waitForMessage<visualization_msgs::Marker>(kNode + "/model_marker", kWait);
  ASSERT_TRUE(marker) << "no latched marker on " << kNode << "/model_marker";
  EXPECT_EQ(marker->header.frame_id, "part");
  EXPECT_EQ(marker->type, visualization_msgs::Marker::TRIANGLE_LIST);
  const auto model = freeform_inspection::loadMesh(param("model_path"), 0.001);
  ASSERT_TRUE(model.status.ok()) << model.status.message;
  EXPECT_EQ(marker->points.size(), 3 * model.mesh.faces.size());
  double max_abs = 0.0;
  for (const auto& p : marker->points) {
    max_abs = std::max({max_abs, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  }
  EXPECT_GT(max_abs, 0.05) << "the blade is ~0.1 m: marker not in metres?";
  EXPECT_LT(max_abs, 0.5) << "the blade is ~0.1 m: mm not converted to metres?";
}

// T_cad_scan of the sample scan, as generate_blade wrote it (4 × 4, row-major).
Eigen::Isometry3d sampleTruth() {
  std::ifstream file(param("sample_truth"));
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      file >> m(r, c);
    }
  }
  EXPECT_TRUE(file) << "cannot read " << param("sample_truth");
  return Eigen::Isometry3d(m);
}

TEST(InspectionNode, RegistersTheSampleScanAndReportsThePartPose) {
  const auto scan = freeform_inspection::loadScan(param("sample_scan"), 1.0);
  ASSERT_TRUE(scan.status.ok()) << scan.status.message;
  const auto response = callInspect(cloudRequest(toCloud(scan.scan.points, "scanner")));
  // Registered; the verdict (deviation against tolerances) is not computed yet.
  EXPECT_EQ(response.status, Inspect::Response::NOT_EVALUATED) << response.message;
  EXPECT_EQ(response.report.registration_status, "ok") << response.message;
  // The report carries the part's pose in the scan frame: inverse(T_cad_scan).
  const Eigen::Isometry3d part_in_scan = tf2::transformToEigen(response.report.transform);
  const Eigen::Isometry3d truth = sampleTruth().inverse();
  EXPECT_LT(
      Eigen::AngleAxisd(part_in_scan.linear().transpose() * truth.linear()).angle() * 180.0 / M_PI,
      0.5);
  EXPECT_LT((part_in_scan.translation() - truth.translation()).norm(), 0.0005);
  EXPECT_EQ(response.report.part_id, "sn-0001");
  EXPECT_EQ(response.report.counts.scan_points, scan.scan.points.size());
  EXPECT_EQ(response.report.counts.scan_faces, 0u) << "an unorganized cloud has no faces";
  EXPECT_EQ(response.report.header.frame_id, "scanner");
  EXPECT_EQ(response.report.transform.child_frame_id, "part");
  const auto result =
      ros::topic::waitForMessage<InspectionReport>(kNode + "/result", ros::Duration(5.0));
  ASSERT_TRUE(result) << "no latched report on ~result";
  EXPECT_EQ(result->part_id, "sn-0001");
}

TEST(InspectionNode, RefusesBadRequestsWithReasonsAndKeepsServing) {
  const auto empty = callInspect(cloudRequest(toCloud({}, "scanner")));
  EXPECT_EQ(empty.status, Inspect::Response::ERROR);
  EXPECT_EQ(empty.report.error_code, "INVALID_INPUT");
  EXPECT_NE(empty.message.find("no finite points"), std::string::npos) << empty.message;

  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto all_nan = callInspect(cloudRequest(toCloud({{nan, nan, nan}, {nan, 0, 0}}, "s")));
  EXPECT_EQ(all_nan.report.error_code, "INVALID_INPUT");

  sensor_msgs::PointCloud2 broken = toCloud({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, "s");
  broken.data.resize(5);  // width·height·point_step no longer matches the data
  const auto inconsistent = callInspect(cloudRequest(broken));
  EXPECT_EQ(inconsistent.report.error_code, "INVALID_INPUT");
  EXPECT_NE(inconsistent.message.find("data holds 5 bytes"), std::string::npos)
      << inconsistent.message;

  Inspect::Request no_scan = cloudRequest(toCloud({}, "s"));
  no_scan.use_last_scan = true;  // nothing was published on `scan`
  EXPECT_EQ(callInspect(no_scan).report.error_code, "NO_SCAN");

  const auto scan = freeform_inspection::loadScan(param("sample_scan"), 1.0);
  ASSERT_TRUE(scan.status.ok());
  freeform_inspection::Points in_mm;
  for (const auto& p : scan.scan.points) {
    in_mm.push_back(1000.0 * p);  // a scan in mm against a CAD in m: refused naming units
  }
  const auto units = callInspect(cloudRequest(toCloud(in_mm, "s")));
  EXPECT_EQ(units.report.error_code, "UNITS_MISMATCH");
  EXPECT_NE(units.message.find("units"), std::string::npos) << units.message;

  const auto good = callInspect(cloudRequest(toCloud(scan.scan.points, "s")));
  EXPECT_EQ(good.report.registration_status, "ok") << "node stopped serving after bad input";
}

TEST(InspectionNode, OrganizedCloudWithNanPixelsIsReadOnItsGrid) {
  // A range image (height > 1) with NaN where the rays miss: the node passes the grid on, the
  // pipeline triangulates it, removes the NaN pixels and counts them.
  namespace analytic = freeform_inspection::analytic;
  const analytic::Pinhole camera{96, 64, 300.0};
  const analytic::OrganizedCloud image =
      analytic::organizedSphere(camera, Eigen::Vector3d(0, 0, 0.3), 0.05);
  sensor_msgs::PointCloud2 cloud = toCloud(image.points, "camera_optical");
  cloud.height = static_cast<std::uint32_t>(image.height);
  cloud.width = static_cast<std::uint32_t>(image.width);
  cloud.row_step = cloud.width * cloud.point_step;
  cloud.is_dense = true;  // drivers lie: the node must not trust it
  std::uint32_t holes = 0;
  for (const auto& p : image.points) {
    holes += p.allFinite() ? 0 : 1;
  }
  ASSERT_GT(holes, 0u);
  const auto response = callInspect(cloudRequest(cloud));
  // A sphere against the blade: never registered, and said so.
  EXPECT_NE(response.report.registration_status, "ok") << response.message;
  EXPECT_EQ(response.report.deviation.n_invalid, holes);
  EXPECT_EQ(response.report.counts.scan_points, image.points.size() - holes);
  EXPECT_GT(response.report.counts.scan_faces, image.points.size() - holes)
      << "an organized cloud must be triangulated on its grid";
}

TEST(InspectionNode, LoadModelRefusesBadPathsAndUnitsAndKeepsTheModel) {
  ASSERT_TRUE(ros::service::waitForService(kNode + "/load_model", kWait));
  LoadModel missing;
  missing.request.path = "/nonexistent/part.stl";
  missing.request.units = "mm";
  ASSERT_TRUE(ros::service::call(kNode + "/load_model", missing));
  EXPECT_FALSE(missing.response.success);
  EXPECT_NE(missing.response.message.find("/nonexistent/part.stl"), std::string::npos)
      << missing.response.message;

  LoadModel bad_units;
  bad_units.request.path = param("model_path");
  bad_units.request.units = "furlong";
  ASSERT_TRUE(ros::service::call(kNode + "/load_model", bad_units));
  EXPECT_FALSE(bad_units.response.success);
  EXPECT_NE(bad_units.response.message.find("furlong"), std::string::npos);

  LoadModel good;
  good.request.path = "package://freeform_inspection/data/blade/blade.stl";
  good.request.units = "mm";
  ASSERT_TRUE(ros::service::call(kNode + "/load_model", good));
  EXPECT_TRUE(good.response.success) << good.response.message;
  EXPECT_GT(good.response.diagonal, 0.05);
  EXPECT_LT(good.response.diagonal, 0.5);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "inspection_node_test");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
