// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <cmath>
#include <string>

#include "io_test_util.h"
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

using io_test::mentions;

class StlTest : public ::testing::Test {
 protected:
  io_test::TempDir dir_;
};

TEST_F(StlTest, AsciiCubeInMillimetres) {
  const std::string path =
      io_test::writeBytes(dir_.file("cube.stl"), io_test::asciiStl(io_test::makeCube(10.0)));
  const MeshLoadResult result = loadMesh(path, 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_vertices, 36u);
  EXPECT_EQ(result.file_faces, 12u);
  EXPECT_TRUE(result.warnings.empty());
  io_test::expectCentimetreCube(result.mesh);
}

TEST_F(StlTest, AsciiTetrahedronToleratesWhitespaceAndCrLf) {
  const std::string text =
      "solid  tetra \r\n"
      "facet normal 0 0 0\r\n outer loop\r\n"
      "\tvertex  1 -1 -1\r\n  vertex -1 -1 1\r\nvertex\t-1 1 -1   \r\n"
      " endloop\r\nendfacet\r\n\r\n"
      "facet normal 0 0 0\nouter loop\nvertex 1 1 1\nvertex -1 1 -1\nvertex -1 -1 1\nendloop\n"
      "endfacet\n"
      "facet normal 0 0 0\nouter loop\nvertex 1 1 1\nvertex -1 -1 1\nvertex 1 -1 -1\nendloop\n"
      "endfacet\n"
      "facet normal 0 0 0\nouter loop\nvertex 1 1 1\nvertex 1 -1 -1\nvertex -1 1 -1\nendloop\n"
      "endfacet\n"
      "endsolid tetra";  // no final newline
  const MeshLoadResult result = loadMesh(io_test::writeBytes(dir_.file("t.STL"), text), 1.0);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.mesh.vertices.size(), 4u);
  EXPECT_EQ(result.mesh.faces.size(), 4u);
  const MeshTopology topology = analyzeTopology(result.mesh);
  EXPECT_TRUE(topology.isOutwardSolid());
  EXPECT_DOUBLE_EQ(topology.signed_volume, 8.0 / 3.0);
  EXPECT_DOUBLE_EQ(topology.area, 8.0 * std::sqrt(3.0));
  io_test::expectOutwardNormals(result.mesh);
}

TEST_F(StlTest, BinaryCubeInMillimetres) {
  const std::string path = io_test::writeBytes(
      dir_.file("cube.stl"), io_test::binaryStl(io_test::makeCube(10.0), "exported by CAD"));
  const MeshLoadResult result = loadMesh(path, 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_vertices, 36u);
  EXPECT_EQ(result.file_faces, 12u);
  io_test::expectCentimetreCube(result.mesh);
}

TEST_F(StlTest, BinaryWhoseHeaderStartsWithSolidIsStillBinary) {
  const std::string path = io_test::writeBytes(
      dir_.file("solid.stl"), io_test::binaryStl(io_test::makeCube(10.0), "solid cube"));
  const MeshLoadResult result = loadMesh(path, 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  io_test::expectCentimetreCube(result.mesh);
}

TEST_F(StlTest, BinaryTetrahedron) {
  const std::string path = io_test::writeBytes(
      dir_.file("tetra.stl"), io_test::binaryStl(io_test::makeTetrahedron(5.0), "tetra"));
  const MeshLoadResult result = loadMesh(path, 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.mesh.vertices.size(), 4u);
  const MeshTopology topology = analyzeTopology(result.mesh);
  EXPECT_TRUE(topology.isOutwardSolid());
  EXPECT_NEAR(topology.signed_volume, 8.0 / 3.0 * std::pow(0.005, 3), 1e-18);
  io_test::expectOutwardNormals(result.mesh);
}

TEST_F(StlTest, BinaryWithLyingCountNamesBothSizes) {
  const std::string path = io_test::writeBytes(
      dir_.file("lying.stl"), io_test::binaryStl(io_test::makeCube(1.0), "lying", 1000000));
  const MeshLoadResult result = loadMesh(path, 1.0);
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "1000000 triangles"));
  EXPECT_TRUE(mentions(result.status.message, "50000084 bytes"));
  EXPECT_TRUE(mentions(result.status.message, "684 bytes"));  // 84 + 12 * 50
}

TEST_F(StlTest, TruncatedBinaryWithSolidHeaderIsReportedAsBinary) {
  std::string bytes = io_test::binaryStl(io_test::makeCube(1.0), "solid but binary");
  bytes.resize(bytes.size() - 20);
  const MeshLoadResult result = loadMesh(io_test::writeBytes(dir_.file("cut.stl"), bytes), 1.0);
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "12 triangles"));
  EXPECT_TRUE(mentions(result.status.message, "684 bytes"));
  EXPECT_TRUE(mentions(result.status.message, "664 bytes"));
}

TEST_F(StlTest, TooShortForBinary) {
  const MeshLoadResult result =
      loadMesh(io_test::writeBytes(dir_.file("short.stl"), std::string("\x01\x02\x03", 3)), 1.0);
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "too short"));
}

TEST_F(StlTest, BinaryWithZeroTrianglesIsDegenerate) {
  const std::string path =
      io_test::writeBytes(dir_.file("empty.stl"), io_test::binaryStl(TriangleMesh{}, "nothing"));
  const MeshLoadResult result = loadMesh(path, 1.0);
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput);
  EXPECT_TRUE(mentions(result.status.message, "has no faces"));
}

TEST_F(StlTest, MalformedAsciiVertexNamesTheLine) {
  const std::string text =
      "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 zero\nvertex 0 1 0\n"
      "endloop\nendfacet\nendsolid x\n";
  const MeshLoadResult result = loadMesh(io_test::writeBytes(dir_.file("bad.stl"), text), 1.0);
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "line 5"));
  EXPECT_TRUE(mentions(result.status.message, "vertex 1 0 zero"));
}

TEST_F(StlTest, AsciiWithUnknownKeywordOrIncompleteFacetFails) {
  const MeshLoadResult unknown = loadMesh(
      io_test::writeBytes(dir_.file("kw.stl"), "solid x\nfacet normal 0 0 1\nbanana\n"), 1.0);
  EXPECT_EQ(unknown.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(unknown.status.message, "line 3"));
  EXPECT_TRUE(mentions(unknown.status.message, "banana"));

  const MeshLoadResult incomplete =
      loadMesh(io_test::writeBytes(dir_.file("two.stl"),
                                   "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                   "vertex 1 0 0\nendloop\nendfacet\nendsolid\n"),
               1.0);
  EXPECT_EQ(incomplete.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(incomplete.status.message, "not a multiple of 3"));
}

TEST_F(StlTest, CollapsedTrianglesAreDroppedWithAWarning) {
  TriangleMesh cube = io_test::makeCube(1.0);
  cube.faces.emplace_back(0, 0, 1);
  const MeshLoadResult result =
      loadMesh(io_test::writeBytes(dir_.file("sliver.stl"), io_test::binaryStl(cube, "x")), 1.0);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_faces, 13u);
  EXPECT_EQ(result.mesh.faces.size(), 12u);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_TRUE(mentions(result.warnings[0], "dropped 1"));
}

}  // namespace
}  // namespace freeform_inspection
