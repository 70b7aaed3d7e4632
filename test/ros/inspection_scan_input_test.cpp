// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// rostest client: the node's other scan inputs. A stamped mesh (pcl_msgs/PolygonMesh) in the
// request or on `scan_mesh` is registered on its own triangles; a cloud far above
// input/max_points is refused, in the request or on `scan`, before it is converted, and the node
// keeps serving.
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "rostest_helpers.h"
#include <gtest/gtest.h>
#include <pcl_msgs/PolygonMesh.h>
#include <ros/ros.h>
#include <tf2_eigen/tf2_eigen.h>

#include "freeform_inspection/io.h"
#include <freeform_inspection/Inspect.h>

namespace {

using freeform_inspection::Inspect;
using namespace freeform_inspection_rostest;  // NOLINT(google-build-using-namespace): test helpers

// A topic in the node's namespace (the nodelet test runs in one).
std::string nodeTopic(const std::string& name) {
  return ros::names::append(ros::names::parentNamespace(nodeName()), name);
}

// The part pose in the scan frame that the mesh scans are placed at.
Eigen::Isometry3d meshTruth() {
  Eigen::Isometry3d T_scan_cad = Eigen::Isometry3d::Identity();
  T_scan_cad.linear() =
      Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.3, -0.8, 0.5).normalized()).toRotationMatrix();
  T_scan_cad.translation() = Eigen::Vector3d(0.12, -0.05, 0.45);
  return T_scan_cad;
}

struct ViewMesh {
  pcl_msgs::PolygonMesh message;
  std::size_t faces = 0;
};

// A partial scan mesh: the CAD triangles whose normals face `view` (a structured-light
// camera's visible side, without occlusion), vertices compacted, placed at meshTruth() in frame
// "scanner". One quad is formed from two neighbouring triangles to exercise the fan.
ViewMesh viewMesh(const Eigen::Vector3d& view) {
  const auto cad = freeform_inspection::loadMesh(param("model_path"), 0.001);
  EXPECT_TRUE(cad.status.ok()) << cad.status.message;
  const Eigen::Isometry3d T_scan_cad = meshTruth();
  std::map<int, std::uint32_t> kept;
  freeform_inspection::Points points;
  ViewMesh mesh;
  for (const auto& face : cad.mesh.faces) {
    const Eigen::Vector3d a = cad.mesh.vertices[face[0]];
    const Eigen::Vector3d normal =
        (cad.mesh.vertices[face[1]] - a).cross(cad.mesh.vertices[face[2]] - a);
    if (normal.dot(view) <= 0.0) {
      continue;
    }
    pcl_msgs::Vertices polygon;
    for (int k = 0; k < 3; ++k) {
      const auto [it, added] = kept.emplace(face[k], static_cast<std::uint32_t>(points.size()));
      if (added) {
        points.push_back(T_scan_cad * cad.mesh.vertices[face[k]]);
      }
      polygon.vertices.push_back(it->second);
    }
    mesh.message.polygons.push_back(polygon);
  }
  mesh.faces = mesh.message.polygons.size();
  mesh.message.cloud = toCloud(points, "scanner");
  mesh.message.header = mesh.message.cloud.header;
  return mesh;
}

void expectMeshPose(const Inspect::Response& response, const std::string& what) {
  const Eigen::Isometry3d found = tf2::transformToEigen(response.report.transform);
  const Eigen::Isometry3d truth = meshTruth();
  EXPECT_LT(angleDeg(found, truth), kPoseToleranceDeg) << what;
  EXPECT_LT((found.translation() - truth.translation()).norm(), kPoseToleranceM)
      << what << ": found t = " << found.translation().transpose() << ", "
      << response.report.registration_status << ": " << response.message;
}

TEST(InspectionNode, ScanMeshInTheRequestIsRegisteredOnItsOwnTriangles) {
  const ViewMesh mesh = viewMesh(Eigen::Vector3d(0.2, 0.3, 1.0).normalized());
  ASSERT_GT(mesh.faces, 1000u);
  Inspect::Request request = cloudRequest(sensor_msgs::PointCloud2());
  request.mesh = mesh.message;
  const auto response = callInspect(request);
  // The CAD's own triangles: nothing deviates, the band holds, the pose is the placement.
  EXPECT_EQ(response.status, Inspect::Response::PASS) << response.message;
  EXPECT_EQ(response.report.registration_status, "ok") << response.message;
  EXPECT_EQ(response.report.counts.scan_faces, mesh.faces) << "the mesh's faces, not a guess";
  EXPECT_EQ(response.report.header.frame_id, "scanner");
  EXPECT_LT(response.report.deviation.rms, 1e-5);
  expectMeshPose(response, "mesh in the request");

  // A polygon naming a vertex the cloud lacks: refused, naming it.
  Inspect::Request broken = request;
  broken.mesh.polygons[7].vertices[1] = broken.mesh.cloud.width + 3;
  const auto refused = callInspect(broken);
  EXPECT_EQ(refused.status, Inspect::Response::ERROR);
  EXPECT_EQ(refused.report.error_code, "INVALID_INPUT");
  EXPECT_NE(refused.message.find("polygon 7 refers to vertex"), std::string::npos)
      << refused.message;

  // A cloud and a mesh in one request: which one to inspect would be a guess.
  Inspect::Request both = request;
  both.cloud = mesh.message.cloud;
  const auto ambiguous = callInspect(both);
  EXPECT_EQ(ambiguous.report.error_code, "INVALID_INPUT");
  EXPECT_NE(ambiguous.message.find("both cloud and mesh"), std::string::npos) << ambiguous.message;
}

TEST(InspectionNode, LastScanOnScanMeshIsInspected) {
  ros::NodeHandle nh;
  ros::Publisher publisher =
      nh.advertise<pcl_msgs::PolygonMesh>(nodeTopic("scan_mesh"), 1, /*latch=*/true);
  ASSERT_TRUE(waitUntil([&] { return publisher.getNumSubscribers() > 0; }, kWait))
      << "the node does not subscribe " << nodeTopic("scan_mesh");
  const ViewMesh mesh = viewMesh(Eigen::Vector3d(0.2, 0.3, 1.0).normalized());
  publisher.publish(mesh.message);
  Inspect::Request request = cloudRequest(sensor_msgs::PointCloud2());
  request.use_last_scan = true;
  // The node may not have taken the message yet: ask until the mesh is the last scan.
  Inspect::Response response;
  ASSERT_TRUE(waitUntil(
      [&] {
        response = callInspect(request);
        return response.report.counts.scan_faces == mesh.faces;
      },
      kInspectWait))
      << "the mesh published on scan_mesh never became the last scan: " << response.message;
  EXPECT_EQ(response.report.registration_status, "ok") << response.message;
  expectMeshPose(response, "mesh on scan_mesh");
}

// The node's input/max_points, as the .test file set it.
int maxPoints() {
  int max_points = 0;
  EXPECT_TRUE(ros::param::get("~max_points", max_points)) << "missing test parameter ~max_points";
  return max_points;
}

// A cloud ten times input/max_points (set low by the .test file so the message stays small).
sensor_msgs::PointCloud2 farTooBigCloud() {
  const auto max_points = static_cast<std::size_t>(maxPoints());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> in_box(-0.05, 0.05);
  freeform_inspection::Points points(10 * max_points);
  for (auto& p : points) {
    p = Eigen::Vector3d(in_box(random), in_box(random), 0.4 + in_box(random));
  }
  return toCloud(points, "scanner");
}

TEST(InspectionNode, FarTooBigCloudIsRefusedBeforeConversionAndTheNodeKeepsServing) {
  const sensor_msgs::PointCloud2 big = farTooBigCloud();
  const std::string limit = "more than input/max_points = " + std::to_string(maxPoints());
  const auto in_request = callInspect(cloudRequest(big));
  EXPECT_EQ(in_request.status, Inspect::Response::ERROR);
  EXPECT_EQ(in_request.report.error_code, "INVALID_INPUT");
  EXPECT_NE(in_request.message.find(limit), std::string::npos) << in_request.message;
  EXPECT_EQ(in_request.report.header.frame_id, "scanner");

  // The same cloud streamed on `scan` and inspected as the last scan.
  ros::NodeHandle nh;
  ros::Publisher publisher =
      nh.advertise<sensor_msgs::PointCloud2>(nodeTopic("scan"), 1, /*latch=*/true);
  ASSERT_TRUE(waitUntil([&] { return publisher.getNumSubscribers() > 0; }, kWait));
  publisher.publish(big);
  Inspect::Request last = cloudRequest(sensor_msgs::PointCloud2());
  last.use_last_scan = true;
  Inspect::Response streamed;
  ASSERT_TRUE(waitUntil(
      [&] {
        streamed = callInspect(last);
        return streamed.message.find(limit) != std::string::npos;
      },
      kInspectWait))
      << streamed.message;
  EXPECT_EQ(streamed.report.error_code, "INVALID_INPUT");

  const auto good = callInspect(cloudRequest(sampleCloud()));
  EXPECT_EQ(good.status, Inspect::Response::PASS) << "node stopped serving: " << good.message;
}

}  // namespace
