// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <cmath>
#include <cstring>
#include <string>

#include "io_test_util.h"
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

using io_test::mentions;

class WriterTest : public ::testing::Test {
 protected:
  io_test::TempDir dir_;
};

TEST_F(WriterTest, StlRoundTripInMillimetres) {
  const TriangleMesh cube = io_test::makeCube(0.01);  // metres
  const std::string path = dir_.file("cube.stl");
  ASSERT_TRUE(saveMeshStl(path, cube, 1000.0).ok());
  const std::string bytes = io_test::readBytes(path);
  ASSERT_EQ(bytes.size(), 84u + 50u * 12u);
  EXPECT_EQ(std::strncmp(bytes.data(), "freeform_inspection", 19), 0);
  EXPECT_EQ(bytes[19], '\0');
  const MeshLoadResult result = loadMesh(path, 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  io_test::expectCentimetreCube(result.mesh);
}

TEST_F(WriterTest, StlStoresFaceNormals) {
  const TriangleMesh cube = io_test::makeCube(1.0);
  const std::string path = dir_.file("n.stl");
  TriangleMesh without_normals = cube;
  without_normals.face_normals.clear();  // computed by the writer then
  ASSERT_TRUE(saveMeshStl(path, without_normals).ok());
  const std::string bytes = io_test::readBytes(path);
  float normal[3];
  std::memcpy(normal, bytes.data() + 84, sizeof(normal));
  EXPECT_EQ(Eigen::Vector3d(normal[0], normal[1], normal[2]), cube.face_normals[0]);
}

TEST_F(WriterTest, PlyMeshRoundTrip) {
  const TriangleMesh tetra = io_test::makeTetrahedron(0.5);
  const std::string path = dir_.file("tetra.ply");
  ASSERT_TRUE(saveMeshPly(path, tetra).ok());
  const MeshLoadResult result = loadMesh(path, 1.0);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.mesh.vertices, tetra.vertices);
  EXPECT_EQ(result.mesh.faces, tetra.faces);
  const MeshTopology topology = analyzeTopology(result.mesh);
  EXPECT_TRUE(topology.isOutwardSolid());
  EXPECT_DOUBLE_EQ(topology.signed_volume, 8.0 / 3.0 * 0.125);
}

TEST_F(WriterTest, PlyMeshScaleIsApplied) {
  const std::string path = dir_.file("mm.ply");
  ASSERT_TRUE(saveMeshPly(path, io_test::makeCube(0.01), 1000.0).ok());
  const MeshLoadResult result = loadMesh(path, 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  io_test::expectCentimetreCube(result.mesh);
}

TEST_F(WriterTest, PointsRoundTripInEveryVariant) {
  const Points points = {{0.1, -0.2, 0.3}, {1000.000001, 2e-7, -3.25}, {0, 0, 0}};
  const Points normals = {{0, 0, 1}, {0.6, 0.8, 0}, {-1, 0, 0}};
  for (const auto type : {PlyCoordinateType::kFloat32, PlyCoordinateType::kFloat64}) {
    for (const bool binary : {true, false}) {
      for (const bool with_normals : {true, false}) {
        const std::string path = dir_.file("points.ply");
        ASSERT_TRUE(
            savePointsPly(path, points, with_normals ? normals : Points{}, type, binary).ok());
        const ScanLoadResult result = loadScan(path, 1.0);
        ASSERT_TRUE(result.status.ok()) << result.status.message;
        ASSERT_EQ(result.scan.points.size(), 3u);
        for (std::size_t i = 0; i < 3; ++i) {
          if (type == PlyCoordinateType::kFloat64) {
            EXPECT_EQ(result.scan.points[i], points[i]);  // exact, in ascii too
          } else {
            EXPECT_EQ(result.scan.points[i], points[i].cast<float>().cast<double>());
          }
        }
        ASSERT_EQ(result.scan.normals.size(), with_normals ? 3u : 0u);
        for (std::size_t i = 0; with_normals && i < 3; ++i) {
          EXPECT_TRUE(result.scan.normals[i].isApprox(normals[i], 1e-7));
        }
      }
    }
  }
}

TEST_F(WriterTest, NonFinitePointsAreWrittenAndRemovedOnLoad) {
  const Points points = {{1, 2, 3}, {std::nan(""), 0, 0}};
  const std::string path = dir_.file("nan.ply");
  ASSERT_TRUE(savePointsPly(path, points, {}, PlyCoordinateType::kFloat64, false).ok());
  const ScanLoadResult result = loadScan(path, 1.0);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.non_finite_removed, 1u);
}

TEST_F(WriterTest, WriteErrorsNameThePath) {
  const std::string path = dir_.file("no_such_dir/out.stl");
  const Status stl = saveMeshStl(path, io_test::makeCube(1.0));
  EXPECT_EQ(stl.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(stl.message, "cannot write '" + path + "'"));
  EXPECT_TRUE(mentions(stl.message, "No such file"));
  const Status ply = saveMeshPly(dir_.file("no_such_dir/out.ply"), io_test::makeCube(1.0));
  EXPECT_TRUE(mentions(ply.message, "cannot write"));
  const Status points = savePointsPly(dir_.file(""), {{0, 0, 0}}, {});
  EXPECT_EQ(points.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(points.message, "cannot write"));
}

TEST_F(WriterTest, InvalidArgumentsAreRejected) {
  TriangleMesh broken = io_test::makeCube(1.0);
  broken.faces.emplace_back(0, 1, 8);
  const Status bad_index = saveMeshPly(dir_.file("b.ply"), broken);
  EXPECT_EQ(bad_index.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(bad_index.message, "face 12 references vertex 8 of 8"));
  const Status bad_scale = saveMeshStl(dir_.file("b.stl"), io_test::makeCube(1.0), 0.0);
  EXPECT_EQ(bad_scale.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(bad_scale.message, "scale must be finite and > 0"));
  const Status bad_normals = savePointsPly(dir_.file("n.ply"), {{0, 0, 0}}, {{0, 0, 1}, {0, 1, 0}});
  EXPECT_EQ(bad_normals.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(bad_normals.message, "2 normals for 1 points"));
}

}  // namespace
}  // namespace freeform_inspection
