// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <cmath>
#include <string>

#include "../../src/core/io/mesh_bytes.h"
#include "io_test_util.h"
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh.h"

// The checked-in files of test/data (see its README.md), written by an independent generator.

#ifndef FREEFORM_TEST_DATA_DIR
#error "FREEFORM_TEST_DATA_DIR must be the absolute path of test/data"
#endif

namespace freeform_inspection {
namespace {

std::string fixture(const std::string& name) {
  return std::string(FREEFORM_TEST_DATA_DIR) + "/" + name;
}

TEST(FixtureFiles, CubeAsciiStl) {
  const MeshLoadResult result = loadMesh(fixture("cube_ascii.stl"), 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_vertices, 36u);
  io_test::expectCentimetreCube(result.mesh);
}

TEST(FixtureFiles, CubeBinaryStlWithSolidHeader) {
  const MeshLoadResult result = loadMesh(fixture("cube_binary_solid_header.stl"), 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_faces, 12u);
  io_test::expectCentimetreCube(result.mesh);
}

TEST(FixtureFiles, TetrahedronDoubleBinaryPly) {
  const MeshLoadResult result = loadMesh(fixture("tetra_double_binary.ply"), 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.mesh.vertices.size(), 4u);
  EXPECT_EQ(result.mesh.faces.size(), 4u);
  EXPECT_EQ(result.mesh.vertices[0], Eigen::Vector3d::Constant(1010.000001 * 0.001));
  EXPECT_EQ(result.mesh.vertices[3].x(), 990.000001 * 0.001);
  const MeshTopology topology = analyzeTopology(result.mesh);
  EXPECT_TRUE(topology.isOutwardSolid());
  EXPECT_NEAR(topology.signed_volume, 8.0 / 3.0 * 1e-6, 1e-15);
  EXPECT_NEAR(topology.area, 8.0 * std::sqrt(3.0) * 1e-4, 1e-13);
  io_test::expectOutwardNormals(result.mesh);
}

TEST(FixtureFiles, CubeQuadsBigEndianPly) {
  const MeshLoadResult result = loadMesh(fixture("cube_quads_big_endian.ply"), 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_faces, 6u);
  io_test::expectCentimetreCube(result.mesh);
}

TEST(FixtureFiles, ScanWithRangeGridAndNormals) {
  const ScanLoadResult result = loadScan(fixture("scan_range_grid.ply"), 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_points, 5u);
  EXPECT_EQ(result.non_finite_removed, 1u);
  ASSERT_EQ(result.scan.points.size(), 4u);
  EXPECT_TRUE(result.scan.faces.empty());
  EXPECT_DOUBLE_EQ(result.scan.points[2].x(), 0.007);
  ASSERT_EQ(result.scan.normals.size(), 4u);
  EXPECT_EQ(result.scan.normals[1], Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(result.scan.normals[2], Eigen::Vector3d(0, 0.6, 0.8));
}

TEST(FixtureFiles, CubeQuadsObj) {
  const MeshLoadResult result = loadMesh(fixture("cube_quads.obj"), 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_faces, 6u);
  io_test::expectCentimetreCube(result.mesh);
}

TEST(FixtureFiles, AsciiPcd) {
  const ScanLoadResult result = loadScan(fixture("cloud_ascii.pcd"), 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_points, 4u);
  EXPECT_EQ(result.non_finite_removed, 1u);
  ASSERT_EQ(result.scan.points.size(), 3u);
  EXPECT_DOUBLE_EQ(result.scan.points[2].z(), 0.009);
}

// The model cache hashes a CAD file's bytes and, on a miss, parses those same bytes: whatever the
// file holds by then, the mesh is the one of the bytes given, and a bad one is named by the path.
TEST(FixtureFiles, AMeshParsedFromBytesAlreadyReadIsThoseBytesMesh) {
  for (const char* name : {"cube_ascii.stl",
                           "cube_binary_solid_header.stl",
                           "tetra_double_binary.ply",
                           "cube_quads_big_endian.ply",
                           "cube_quads.obj"}) {
    const MeshLoadResult from_path = loadMesh(fixture(name), 0.001);
    const MeshLoadResult from_bytes =
        io_internal::loadMeshFromBytes(fixture(name), io_test::readBytes(fixture(name)), 0.001);
    ASSERT_TRUE(from_bytes.status.ok()) << name << ": " << from_bytes.status.message;
    EXPECT_EQ(from_bytes.mesh.vertices, from_path.mesh.vertices) << name;
    EXPECT_EQ(from_bytes.mesh.faces, from_path.mesh.faces) << name;
    EXPECT_EQ(from_bytes.file_faces, from_path.file_faces) << name;
    EXPECT_EQ(from_bytes.warnings, from_path.warnings) << name;
  }
  // The file at the path now holds a tetrahedron; the bytes read before were the cube's.
  const MeshLoadResult cube = io_internal::loadMeshFromBytes(
      fixture("tetra_double_binary.ply"), io_test::readBytes(fixture("cube_quads.obj")), 0.001);
  EXPECT_FALSE(cube.status.ok()) << "OBJ bytes parsed as the PLY the extension names";
  EXPECT_NE(cube.status.message.find("tetra_double_binary.ply"), std::string::npos)
      << cube.status.message;
  io_test::TempDir dir;
  const std::string path = dir.file("part.obj");
  const std::string cube_bytes = io_test::readBytes(fixture("cube_quads.obj"));
  io_test::writeBytes(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const MeshLoadResult replaced = io_internal::loadMeshFromBytes(path, cube_bytes, 0.001);
  ASSERT_TRUE(replaced.status.ok()) << replaced.status.message;
  EXPECT_EQ(replaced.file_faces, 6u);
  io_test::expectCentimetreCube(replaced.mesh);
  EXPECT_EQ(loadMesh(path, 0.001).mesh.faces.size(), 1u);
}

}  // namespace
}  // namespace freeform_inspection
