// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// Winding repair: randomly reversed faces of a closed sphere and of an open sheet come back
// outward; a sphere wound inside out is turned; border edges of open surfaces are found.
#include "freeform_inspection/mesh_orientation.h"

#include <random>

#include "analytic_shapes.h"
#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

// Faces whose normal points away from the origin (all of them, for a sphere about it).
std::size_t outwardFaces(const TriangleMesh& mesh) {
  std::size_t outward = 0;
  const Points normals = computeFaceNormals(mesh.vertices, mesh.faces);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Eigen::Vector3d centre =
        (mesh.vertices[mesh.faces[f][0]] + mesh.vertices[mesh.faces[f][1]] +
         mesh.vertices[mesh.faces[f][2]]) /
        3.0;
    outward += normals[f].dot(centre) > 0.0 ? 1 : 0;
  }
  return outward;
}

// Reverses each face with probability `share`; returns how many.
std::size_t scramble(TriangleMesh* mesh, double share, unsigned seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution flip(share);
  std::size_t flipped = 0;
  for (auto& f : mesh->faces) {
    if (flip(rng)) {
      std::swap(f[1], f[2]);
      ++flipped;
    }
  }
  return flipped;
}

TEST(MeshOrientation, ScrambledClosedSphereComesBackOutward) {
  for (const double share : {0.1, 0.5, 0.9}) {
    TriangleMesh mesh = test::icosphere(1.0, 3);
    const std::size_t scrambled = scramble(&mesh, share, 11);
    const OrientationResult result = orientOutward(&mesh);
    std::printf("share %.1f: %zu reversed, %zu flipped back (seed 11)\n",
                share,
                scrambled,
                result.flipped_faces);
    EXPECT_EQ(result.components, 1u);
    EXPECT_EQ(result.flipped_faces, scrambled);
    EXPECT_EQ(outwardFaces(mesh), mesh.faces.size());
    EXPECT_TRUE(analyzeTopology(mesh).isOutwardSolid());
    EXPECT_TRUE(borderEdgeMasks(mesh).empty());
  }
}

TEST(MeshOrientation, InsideOutSphereIsTurnedAndAConsistentOneIsLeftAlone) {
  TriangleMesh inside_out = test::flipped(test::icosphere(1.0, 2));
  const OrientationResult turned = orientOutward(&inside_out);
  EXPECT_EQ(turned.reversed_components, 1u);
  EXPECT_EQ(turned.flipped_faces, inside_out.faces.size());
  EXPECT_EQ(outwardFaces(inside_out), inside_out.faces.size());
  TriangleMesh good = test::icosphere(1.0, 2);
  const TriangleMesh before = good;
  EXPECT_EQ(orientOutward(&good).flipped_faces, 0u);
  EXPECT_EQ(good.faces, before.faces);
}

TEST(MeshOrientation, OpenSheetKeepsItsMajorityWindingAndTwoPiecesAreHandledApart) {
  TriangleMesh sheet = test::planarGrid(1.0, 10);  // normals +z, 200 faces
  const std::size_t scrambled = scramble(&sheet, 0.3, 5);
  // A second, separate closed piece wound inside out, far away.
  TriangleMesh ball = test::flipped(test::icosphere(0.1, 2));
  const int offset = static_cast<int>(sheet.vertices.size());
  for (const auto& v : ball.vertices) {
    sheet.vertices.push_back(v + Eigen::Vector3d(5.0, 0.0, 0.0));
  }
  for (const auto& f : ball.faces) {
    sheet.faces.push_back(f + Eigen::Vector3i::Constant(offset));
  }
  const OrientationResult result = orientOutward(&sheet);
  EXPECT_EQ(result.components, 2u);
  EXPECT_EQ(result.flipped_faces, scrambled + ball.faces.size());
  for (std::size_t f = 0; f < 200; ++f) {
    EXPECT_GT(sheet.face_normals[f].z(), 0.99) << f;
  }
  // The sheet's border: 40 edges of the 10 x 10 grid, on 40 faces.
  const auto masks = borderEdgeMasks(sheet);
  ASSERT_EQ(masks.size(), sheet.faces.size());
  int border_edges = 0;
  for (const auto mask : masks) {
    border_edges += ((mask & 1) != 0) + ((mask & 2) != 0) + ((mask & 4) != 0);
  }
  EXPECT_EQ(border_edges, 40);
}

}  // namespace
}  // namespace freeform_inspection
