// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/mesh.h"

#include <cmath>

#include "io_test_util.h"
#include <gtest/gtest.h>

namespace freeform_inspection {
namespace {

using io_test::makeCube;
using io_test::makeTetrahedron;

TEST(MeshTopology, CubeIsClosedOutwardSolidWithExactVolumeAndArea) {
  const MeshTopology topology = analyzeTopology(makeCube(2.0));
  EXPECT_TRUE(topology.isClosedManifold());
  EXPECT_TRUE(topology.isOutwardSolid());
  EXPECT_EQ(topology.edges, 18u);  // 12 cube edges + 6 face diagonals
  EXPECT_EQ(topology.boundary_edges, 0u);
  EXPECT_EQ(topology.non_manifold_edges, 0u);
  EXPECT_EQ(topology.misoriented_edges, 0u);
  EXPECT_EQ(topology.degenerate_faces, 0u);
  EXPECT_EQ(topology.unused_vertices, 0u);
  EXPECT_DOUBLE_EQ(topology.signed_volume, 8.0);
  EXPECT_DOUBLE_EQ(topology.area, 24.0);
}

TEST(MeshTopology, TetrahedronVolumeAndAreaAreExact) {
  const MeshTopology topology = analyzeTopology(makeTetrahedron(1.0));
  EXPECT_TRUE(topology.isOutwardSolid());
  EXPECT_EQ(topology.edges, 6u);
  EXPECT_DOUBLE_EQ(topology.signed_volume, 8.0 / 3.0);
  EXPECT_DOUBLE_EQ(topology.area, 8.0 * std::sqrt(3.0));
}

TEST(MeshTopology, InvertedCubeHasNegativeVolume) {
  TriangleMesh cube = makeCube(1.0);
  for (auto& f : cube.faces) {
    std::swap(f[1], f[2]);
  }
  const MeshTopology topology = analyzeTopology(cube);
  EXPECT_TRUE(topology.isClosedManifold());
  EXPECT_FALSE(topology.isOutwardSolid());
  EXPECT_DOUBLE_EQ(topology.signed_volume, -1.0);
}

TEST(MeshTopology, FlippedFaceGivesMisorientedEdges) {
  TriangleMesh cube = makeCube(1.0);
  std::swap(cube.faces[0][1], cube.faces[0][2]);
  const MeshTopology topology = analyzeTopology(cube);
  EXPECT_EQ(topology.misoriented_edges, 3u);
  EXPECT_EQ(topology.boundary_edges, 0u);
  EXPECT_FALSE(topology.isClosedManifold());
}

TEST(MeshTopology, RemovedFaceGivesBoundaryEdges) {
  TriangleMesh cube = makeCube(1.0);
  cube.faces.pop_back();
  const MeshTopology topology = analyzeTopology(cube);
  EXPECT_EQ(topology.boundary_edges, 3u);
  EXPECT_FALSE(topology.isClosedManifold());
  EXPECT_DOUBLE_EQ(topology.area, 5.5);
}

TEST(MeshTopology, ExtraFaceOnAnEdgeIsNonManifoldAndUnusedVertexIsCounted) {
  TriangleMesh cube = makeCube(1.0);
  cube.vertices.emplace_back(5.0, 5.0, 5.0);  // unused
  cube.vertices.emplace_back(0.5, -1.0, 0.0);
  cube.faces.emplace_back(0, 1, 9);  // third face on edge 0-1
  const MeshTopology topology = analyzeTopology(cube);
  EXPECT_EQ(topology.non_manifold_edges, 1u);
  EXPECT_EQ(topology.unused_vertices, 1u);
  EXPECT_FALSE(topology.isClosedManifold());
}

TEST(MeshTopology, DegenerateFacesAreCounted) {
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  mesh.faces = {{0, 1, 2}, {0, 0, 3}, {0, 1, 3}};  // collinear, repeated index, fine
  EXPECT_EQ(analyzeTopology(mesh).degenerate_faces, 2u);
}

TEST(MeshHelpers, WeldingACubeSoupGivesEightVertices) {
  const TriangleMesh cube = makeCube(1.0);
  Points corners;
  for (const auto& f : cube.faces) {
    for (int c = 0; c < 3; ++c) {
      corners.push_back(cube.vertices[static_cast<std::size_t>(f[c])]);
    }
  }
  ASSERT_EQ(corners.size(), 36u);
  const TriangleMesh welded = weldTriangleSoup(corners);
  EXPECT_EQ(welded.vertices.size(), 8u);
  EXPECT_EQ(welded.faces.size(), 12u);
  EXPECT_EQ(welded.face_normals.size(), 12u);
  const MeshTopology topology = analyzeTopology(welded);
  EXPECT_TRUE(topology.isOutwardSolid());
  EXPECT_DOUBLE_EQ(topology.signed_volume, 1.0);
}

TEST(MeshHelpers, WeldingDropsCollapsedTrianglesAndKeepsNearbyDistinctCorners) {
  const Points corners = {{0, 0, 0},
                          {1, 0, 0},
                          {0, 1, 0},  // fine
                          {0, 0, 0},
                          {0, 0, 0},
                          {1, 0, 0},  // two corners coincide
                          {0, 0, 0},
                          {1e-12, 0, 0},
                          {0, 1, 0}};  // distinct, however close
  const TriangleMesh welded = weldTriangleSoup(corners);
  EXPECT_EQ(welded.faces.size(), 2u);
  EXPECT_EQ(welded.vertices.size(), 4u);
}

TEST(MeshHelpers, FaceNormalsAreUnitOutwardAndZeroForDegenerateFaces) {
  const TriangleMesh cube = makeCube(3.0);
  io_test::expectOutwardNormals(cube);
  const Points normals = computeFaceNormals({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}});
  ASSERT_EQ(normals.size(), 1u);
  EXPECT_EQ(normals[0], Eigen::Vector3d::Zero());
}

TEST(MeshHelpers, BoundingBox) {
  const BoundingBox empty = computeBoundingBox({});
  EXPECT_EQ(empty.min, Eigen::Vector3d::Zero());
  EXPECT_EQ(empty.max, Eigen::Vector3d::Zero());
  const BoundingBox box = computeBoundingBox({{1, -2, 3}, {-1, 5, 0}, {0, 0, 7}});
  EXPECT_EQ(box.min, Eigen::Vector3d(-1, -2, 0));
  EXPECT_EQ(box.max, Eigen::Vector3d(1, 5, 7));
  EXPECT_DOUBLE_EQ(box.diagonal(), std::sqrt(4.0 + 49.0 + 49.0));
}

TEST(Status, CodesHaveStableNames) {
  EXPECT_STREQ(toString(StatusCode::kOk), "ok");
  EXPECT_STREQ(toString(StatusCode::kInvalidInput), "invalid_input");
  EXPECT_STREQ(toString(StatusCode::kDegenerateInput), "degenerate_input");
  EXPECT_STREQ(toString(StatusCode::kNotImplemented), "not_implemented");
}

}  // namespace
}  // namespace freeform_inspection
