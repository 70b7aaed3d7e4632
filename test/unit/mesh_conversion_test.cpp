// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// pcl_msgs/PolygonMesh → Scan (src/ros/mesh_conversion.cpp): the vertex cloud read like any
// PointCloud2, polygons fanned into triangles with their winding kept, and malformed polygons
// refused naming the polygon. No ROS master: meshToScan is a plain function.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "conversions.h"
#include <gtest/gtest.h>

namespace freeform_inspection_ros {
namespace {

using sensor_msgs::PointField;

// A mesh whose cloud holds `points` as float32 x, y, z (12-byte step) laid out `width` wide.
pcl_msgs::PolygonMesh meshOf(const std::vector<Eigen::Vector3f>& points,
                             const std::vector<std::vector<std::uint32_t>>& polygons,
                             std::uint32_t width = 0) {
  pcl_msgs::PolygonMesh mesh;
  mesh.header.frame_id = "scanner";
  auto& cloud = mesh.cloud;
  cloud.header = mesh.header;
  cloud.width = width == 0 ? static_cast<std::uint32_t>(points.size()) : width;
  cloud.height = static_cast<std::uint32_t>(points.size()) / cloud.width;
  const char* names[] = {"x", "y", "z"};
  for (std::uint32_t i = 0; i < 3; ++i) {
    PointField field;
    field.name = names[i];
    field.offset = 4 * i;
    field.datatype = PointField::FLOAT32;
    field.count = 1;
    cloud.fields.push_back(field);
  }
  cloud.point_step = 12;
  cloud.row_step = cloud.width * cloud.point_step;
  cloud.data.resize(points.size() * 12);
  std::memcpy(cloud.data.data(), points.data(), cloud.data.size());
  for (const auto& corners : polygons) {
    pcl_msgs::Vertices polygon;
    polygon.vertices = corners;
    mesh.polygons.push_back(polygon);
  }
  return mesh;
}

const std::vector<Eigen::Vector3f> kSquareAndApex = {
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5F, 0.5F, 1}};

TEST(MeshConversion, TrianglesPassThroughAndQuadsAreFannedKeepingTheirWinding) {
  const auto converted = meshToScan(meshOf(kSquareAndApex, {{0, 1, 2, 3}, {0, 1, 4}}));
  ASSERT_TRUE(converted.status.ok()) << converted.status.message;
  ASSERT_EQ(converted.scan.points.size(), 5u);
  EXPECT_TRUE(converted.scan.points[4].isApprox(Eigen::Vector3d(0.5, 0.5, 1.0)));
  ASSERT_EQ(converted.scan.faces.size(), 3u);
  EXPECT_EQ(converted.scan.faces[0], Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(converted.scan.faces[1], Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(converted.scan.faces[2], Eigen::Vector3i(0, 1, 4));
  // Both quad triangles keep the quad's counter-clockwise turn about +z.
  for (int f = 0; f < 2; ++f) {
    const auto& t = converted.scan.faces[f];
    const auto& p = converted.scan.points;
    EXPECT_GT((p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).z(), 0.0) << "face " << f;
  }
}

TEST(MeshConversion, AGridShapedVertexCloudIsNotTriangulatedAgainOnItsGrid) {
  // pcl::toPCLPointCloud2 of an organized cloud keeps width × height; the polygons rule.
  const auto converted = meshToScan(
      meshOf({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 1, 3}, {0, 3, 2}}, /*width=*/2));
  ASSERT_TRUE(converted.status.ok()) << converted.status.message;
  EXPECT_FALSE(converted.scan.isOrganized());
  EXPECT_EQ(converted.scan.faces.size(), 2u);
}

TEST(MeshConversion, NoPolygonsIsAPlainCloud) {
  const auto converted = meshToScan(meshOf(kSquareAndApex, {}));
  ASSERT_TRUE(converted.status.ok()) << converted.status.message;
  EXPECT_EQ(converted.scan.points.size(), 5u);
  EXPECT_TRUE(converted.scan.faces.empty());
}

TEST(MeshConversion, OutOfRangeVertexIsRefusedNamingPolygonAndVertex) {
  const auto converted = meshToScan(meshOf(kSquareAndApex, {{0, 1, 2}, {0, 1, 5}}));
  EXPECT_EQ(converted.status.code, fi::StatusCode::kInvalidInput);
  EXPECT_NE(converted.status.message.find("polygon 1 refers to vertex 5"), std::string::npos)
      << converted.status.message;
  EXPECT_TRUE(converted.scan.points.empty()) << "nothing half-converted is handed on";
  EXPECT_TRUE(converted.scan.faces.empty());
}

TEST(MeshConversion, PolygonWithFewerThanThreeVerticesIsRefused) {
  const auto converted = meshToScan(meshOf(kSquareAndApex, {{0, 1, 2}, {3, 4}}));
  EXPECT_EQ(converted.status.code, fi::StatusCode::kInvalidInput);
  EXPECT_NE(converted.status.message.find("polygon 1 has 2 vertices"), std::string::npos)
      << converted.status.message;
}

TEST(MeshConversion, BrokenVertexCloudIsRefusedLikeAnyCloud) {
  auto mesh = meshOf(kSquareAndApex, {{0, 1, 2}});
  mesh.cloud.data.resize(7);
  const auto converted = meshToScan(mesh);
  EXPECT_EQ(converted.status.code, fi::StatusCode::kInvalidInput);
  EXPECT_NE(converted.status.message.find("data holds 7 bytes"), std::string::npos)
      << converted.status.message;
}

}  // namespace
}  // namespace freeform_inspection_ros
