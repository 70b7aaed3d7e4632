// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <string>

#include "io_test_util.h"
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

using io_test::mentions;

// 10 mm cube: quads in all four corner syntaxes, negative indices, and the usual noise.
constexpr char kCubeObj[] =
    "# exported by hand\r\n"
    "mtllib cube.mtl\n"
    "o cube\n"
    "v 0 0 0\nv 10 0 0\nv 0 10 0\nv 10 10 0\n"
    "v 0 0 10\nv 10 0 10 1.0\nv 0 10 10\nv 10 10 10 0.5 0.5 0.5\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 -1\n"
    "g sides\nusemtl steel\ns off\n"
    "f 1 3 4 2\n"
    "f 5/1 6/2 8/3 7/1\n"
    "f 1//1 2//1 6//1 5//1\n"
    "f 3/1/1 7/2/1 8/3/1 4/1/1\n"
    "f -8 -4 -2 -6\n"        // 1 5 7 3
    "f\t-7   -5 -1 -3  \n";  // 2 4 8 6

class ObjTest : public ::testing::Test {
 protected:
  MeshLoadResult load(const std::string& text, double scale = 1.0) {
    return loadMesh(io_test::writeBytes(dir_.file("m.obj"), text), scale);
  }

  io_test::TempDir dir_;
};

TEST_F(ObjTest, QuadCubeWithSlashesAndNegativeIndices) {
  const MeshLoadResult result = load(kCubeObj, 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_vertices, 8u);
  EXPECT_EQ(result.file_faces, 6u);
  EXPECT_TRUE(result.warnings.empty());
  EXPECT_EQ(result.mesh.faces[0], Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(result.mesh.faces[1], Eigen::Vector3i(0, 3, 1));
  EXPECT_EQ(result.mesh.faces[8], Eigen::Vector3i(0, 4, 6));
  io_test::expectCentimetreCube(result.mesh);
}

TEST_F(ObjTest, TetrahedronAsScanKeepsVerticesAndFaces) {
  const ScanLoadResult result =
      loadScan(io_test::writeBytes(dir_.file("t.OBJ"),
                                   "v 1 1 1\nv 1 -1 -1\nv -1 1 -1\nv -1 -1 1\n"
                                   "f 2 4 3\nf 1 3 4\nf 1 4 2\nf 1 2 3\n"),
               1.0);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_points, 4u);
  EXPECT_EQ(result.scan.faces, io_test::makeTetrahedron(1.0).faces);
}

TEST_F(ObjTest, ForwardReferencesAreAllowed) {
  const MeshLoadResult result = load("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.mesh.faces.size(), 1u);
}

TEST_F(ObjTest, IndexOutOfRangeNamesTheLine) {
  const MeshLoadResult result = load("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 3\nf 1 2 9\n");
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "line 6"));
  EXPECT_TRUE(mentions(result.status.message, "vertex index 9 but the file has 3 vertices"));
}

TEST_F(ObjTest, IndexZeroIsInvalid) {
  const MeshLoadResult result = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "line 4"));
  EXPECT_TRUE(mentions(result.status.message, "index 0"));
}

TEST_F(ObjTest, RelativeIndexBeforeEnoughVertices) {
  const MeshLoadResult result = load("v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n");
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "line 3"));
  EXPECT_TRUE(mentions(result.status.message, "relative vertex index -3"));
}

TEST_F(ObjTest, MalformedLinesNameTheLine) {
  const MeshLoadResult vertex = load("v 0 0 0\nv 1 0\n");
  EXPECT_EQ(vertex.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(vertex.status.message, "line 2"));
  EXPECT_TRUE(mentions(vertex.status.message, "expected 'v x y z'"));

  const MeshLoadResult corner = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x/3\n");
  EXPECT_EQ(corner.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(corner.status.message, "line 4"));
  EXPECT_TRUE(mentions(corner.status.message, "bad face corner 'x/3'"));
}

TEST_F(ObjTest, VerticesOnlyIsNotACadModel) {
  const MeshLoadResult result = load("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput);
  EXPECT_TRUE(mentions(result.status.message, "has no faces"));
}

TEST_F(ObjTest, TwoCornerFaceIsDroppedWithAWarning) {
  const MeshLoadResult result = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n");
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_faces, 2u);
  EXPECT_EQ(result.mesh.faces.size(), 1u);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_TRUE(mentions(result.warnings[0], "fewer than 3 vertices"));
}

}  // namespace
}  // namespace freeform_inspection
