// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// One-ring connectivity (buildMeshAdjacency): exact counts on small solids and grids, and a
// brute-force comparison on a shuffled icosphere.
#include "freeform_inspection/mesh_adjacency.h"

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "analytic_shapes.h"
#include "test_shapes.h"
#include <gtest/gtest.h>

namespace freeform_inspection {
namespace {

using test::icosphere;
using test::planarGrid;
using test::torus;

std::size_t at(int i) {
  return static_cast<std::size_t>(i);
}

Triangles tetrahedronFaces() {
  return {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
}

// Unit cube with two outward triangles per side (the box of test_shapes.h).
Triangles cubeFaces() {
  return test::makeBox(Eigen::Vector3d::Ones()).faces;
}

std::vector<int> neighboursOf(const MeshAdjacency& adjacency, std::size_t v) {
  return {adjacency.vertex_neighbours.begin() +
              static_cast<std::ptrdiff_t>(adjacency.vertex_neighbour_offsets[v]),
          adjacency.vertex_neighbours.begin() +
              static_cast<std::ptrdiff_t>(adjacency.vertex_neighbour_offsets[v + 1])};
}

std::vector<int> facesOf(const MeshAdjacency& adjacency, std::size_t v) {
  return {adjacency.vertex_faces.begin() +
              static_cast<std::ptrdiff_t>(adjacency.vertex_face_offsets[v]),
          adjacency.vertex_faces.begin() +
              static_cast<std::ptrdiff_t>(adjacency.vertex_face_offsets[v + 1])};
}

std::size_t boundaryCount(const MeshAdjacency& adjacency) {
  return static_cast<std::size_t>(
      std::count(adjacency.boundary_vertex.begin(), adjacency.boundary_vertex.end(), true));
}

// The obvious O(n log n)-with-trees construction, as the reference.
struct Reference {
  std::map<std::pair<int, int>, std::vector<int>> edge_faces;
  std::vector<std::set<int>> neighbours;
  std::vector<std::vector<int>> faces;
};

Reference reference(const Triangles& faces, std::size_t vertex_count) {
  Reference ref;
  ref.neighbours.resize(vertex_count);
  ref.faces.resize(vertex_count);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const int a = faces[i][c];
      const int b = faces[i][(c + 1) % 3];
      ref.edge_faces[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(i));
      ref.neighbours[at(a)].insert(b);
      ref.neighbours[at(b)].insert(a);
      ref.faces[at(a)].push_back(static_cast<int>(i));
    }
  }
  return ref;
}

void expectMatchesReference(const Triangles& faces, std::size_t vertex_count) {
  const MeshAdjacency adjacency = buildMeshAdjacency(faces, vertex_count);
  const Reference ref = reference(faces, vertex_count);
  ASSERT_EQ(adjacency.edges.size(), ref.edge_faces.size());
  std::size_t i = 0;
  for (const auto& [key, users] : ref.edge_faces) {
    const MeshEdge& e = adjacency.edges[i++];
    EXPECT_EQ(std::make_pair(e.v0, e.v1), key);
    EXPECT_EQ(e.f0, users[0]);
    EXPECT_EQ(e.f1, users.size() > 1 ? users[1] : -1);
  }
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const std::vector<int> expected(ref.neighbours[v].begin(), ref.neighbours[v].end());
    EXPECT_EQ(neighboursOf(adjacency, v), expected) << "vertex " << v;
    EXPECT_EQ(facesOf(adjacency, v), ref.faces[v]) << "vertex " << v;
  }
}

void expectCsrSizes(const MeshAdjacency& adjacency, std::size_t vertices, std::size_t faces) {
  ASSERT_EQ(adjacency.vertex_face_offsets.size(), vertices + 1);
  ASSERT_EQ(adjacency.vertex_neighbour_offsets.size(), vertices + 1);
  ASSERT_EQ(adjacency.boundary_vertex.size(), vertices);
  EXPECT_EQ(adjacency.vertex_faces.size(), 3 * faces);
  EXPECT_EQ(adjacency.vertex_neighbours.size(), 2 * adjacency.edges.size());
}

TEST(MeshAdjacency, TetrahedronIsClosedWithThreeNeighboursEach) {
  const MeshAdjacency adjacency = buildMeshAdjacency(tetrahedronFaces(), 4);
  expectCsrSizes(adjacency, 4, 4);
  EXPECT_EQ(adjacency.edges.size(), 6u);  // E = V + F − 2
  EXPECT_EQ(boundaryCount(adjacency), 0u);
  EXPECT_EQ(adjacency.non_manifold_edges, 0u);
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_EQ(facesOf(adjacency, v).size(), 3u);
    std::vector<int> others;
    for (int w = 0; w < 4; ++w) {
      if (at(w) != v) {
        others.push_back(w);
      }
    }
    EXPECT_EQ(neighboursOf(adjacency, v), others);
  }
  for (const MeshEdge& e : adjacency.edges) {
    EXPECT_LT(e.v0, e.v1);
    EXPECT_GE(e.f1, 0);
  }
}

TEST(MeshAdjacency, CubeHasEighteenEdgesAndEulerCharacteristicTwo) {
  const MeshAdjacency adjacency = buildMeshAdjacency(cubeFaces(), 8);
  expectCsrSizes(adjacency, 8, 12);
  EXPECT_EQ(adjacency.edges.size(), 18u);  // 12 sides + 6 diagonals = 8 + 12 − 2
  EXPECT_EQ(boundaryCount(adjacency), 0u);
  // On a closed manifold every vertex has as many faces as edges around it.
  std::size_t total = 0;
  for (std::size_t v = 0; v < 8; ++v) {
    total += neighboursOf(adjacency, v).size();
    EXPECT_EQ(facesOf(adjacency, v).size(), neighboursOf(adjacency, v).size()) << "vertex " << v;
  }
  EXPECT_EQ(total, 36u);
  expectMatchesReference(cubeFaces(), 8);
}

TEST(MeshAdjacency, OpenGridBoundaryIsThePerimeter) {
  constexpr int kCells = 4;
  const TriangleMesh grid = planarGrid(1.0, kCells);
  const MeshAdjacency adjacency = buildMeshAdjacency(grid.faces, grid.vertices.size());
  expectCsrSizes(adjacency, 25, 32);
  EXPECT_EQ(adjacency.edges.size(), 56u);  // 2n(n+1) axis-aligned + n² diagonals
  EXPECT_EQ(boundaryCount(adjacency), 4u * kCells);
  EXPECT_EQ(adjacency.non_manifold_edges, 0u);
  const std::size_t centre = 2 * (kCells + 1) + 2;
  EXPECT_FALSE(adjacency.boundary_vertex[centre]);
  EXPECT_EQ(neighboursOf(adjacency, centre).size(), 6u);
  EXPECT_EQ(facesOf(adjacency, centre).size(), 6u);
  EXPECT_EQ(neighboursOf(adjacency, 0), (std::vector<int>{1, 5, 6}));  // diagonal corner
  EXPECT_EQ(facesOf(adjacency, 0).size(), 2u);
  EXPECT_EQ(neighboursOf(adjacency, kCells), (std::vector<int>{3, 9}));
  EXPECT_EQ(facesOf(adjacency, kCells).size(), 1u);
  std::size_t boundary_edges = 0;
  for (const MeshEdge& e : adjacency.edges) {
    boundary_edges += e.f1 < 0 ? 1 : 0;
  }
  EXPECT_EQ(boundary_edges, 4u * kCells);
  expectMatchesReference(grid.faces, grid.vertices.size());
}

TEST(MeshAdjacency, ThreeTrianglesOnOneEdgeAreNonManifold) {
  const Triangles faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const MeshAdjacency adjacency = buildMeshAdjacency(faces, 5);
  EXPECT_EQ(adjacency.non_manifold_edges, 1u);
  ASSERT_EQ(adjacency.edges.size(), 7u);
  const MeshEdge& shared = adjacency.edges.front();
  EXPECT_EQ(shared.v0, 0);
  EXPECT_EQ(shared.v1, 1);
  EXPECT_EQ(shared.f0, 0);
  EXPECT_EQ(shared.f1, 1);
  EXPECT_EQ(boundaryCount(adjacency), 5u);  // the six outer edges are boundary edges
  EXPECT_EQ(neighboursOf(adjacency, 0), (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(facesOf(adjacency, 1), (std::vector<int>{0, 1, 2}));
}

TEST(MeshAdjacency, ShuffledIcosphereMatchesBruteForce) {
  constexpr unsigned kSeed = 20260107;
  TriangleMesh sphere = icosphere(1.0, 3);
  std::mt19937 rng(kSeed);
  std::shuffle(sphere.faces.begin(), sphere.faces.end(), rng);
  for (auto& f : sphere.faces) {  // rotate corners too: the edge order must not depend on it
    std::rotate(f.data(), f.data() + rng() % 3, f.data() + 3);
  }
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  const MeshAdjacency adjacency = buildMeshAdjacency(sphere.faces, sphere.vertices.size());
  EXPECT_EQ(adjacency.edges.size(), sphere.vertices.size() + sphere.faces.size() - 2);
  EXPECT_EQ(boundaryCount(adjacency), 0u);
  EXPECT_TRUE(std::is_sorted(
      adjacency.edges.begin(), adjacency.edges.end(), [](const MeshEdge& a, const MeshEdge& b) {
        return std::make_pair(a.v0, a.v1) < std::make_pair(b.v0, b.v1);
      }));
  expectMatchesReference(sphere.faces, sphere.vertices.size());
}

TEST(MeshAdjacency, TorusHasEulerCharacteristicZero) {
  const TriangleMesh ring = torus(2.0, 0.5, 24, 12);
  const MeshAdjacency adjacency = buildMeshAdjacency(ring.faces, ring.vertices.size());
  const auto euler = static_cast<long>(ring.vertices.size()) -
                     static_cast<long>(adjacency.edges.size()) +
                     static_cast<long>(ring.faces.size());
  EXPECT_EQ(euler, 0);
  EXPECT_EQ(boundaryCount(adjacency), 0u);
  for (std::size_t v = 0; v < ring.vertices.size(); ++v) {
    ASSERT_EQ(neighboursOf(adjacency, v).size(), 6u) << "vertex " << v;
  }
}

TEST(MeshAdjacency, EmptyMeshGivesEmptyRanges) {
  const MeshAdjacency adjacency = buildMeshAdjacency({}, 3);
  expectCsrSizes(adjacency, 3, 0);
  EXPECT_TRUE(adjacency.edges.empty());
  EXPECT_EQ(adjacency.vertex_face_offsets, (std::vector<std::size_t>{0, 0, 0, 0}));
  EXPECT_EQ(boundaryCount(adjacency), 0u);
}

TEST(MeshAdjacency, OutOfRangeAndRepeatedIndexFacesAreSkipped) {
  const Triangles faces = {{0, 1, 2}, {0, 1, 7}, {-1, 0, 1}, {2, 2, 1}};
  const MeshAdjacency adjacency = buildMeshAdjacency(faces, 3);
  expectCsrSizes(adjacency, 3, 1);
  EXPECT_EQ(adjacency.edges.size(), 3u);
  EXPECT_EQ(boundaryCount(adjacency), 3u);
  for (std::size_t v = 0; v < 3; ++v) {
    EXPECT_EQ(facesOf(adjacency, v), (std::vector<int>{0}));
  }
}

}  // namespace
}  // namespace freeform_inspection
