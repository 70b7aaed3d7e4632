// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/mesh_adjacency.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace freeform_inspection {
namespace {

// Half-edges grouped by their lower vertex (counting sort), each stored as a packed 64-bit key
// (higher vertex << 32 | face). Sorting a bucket of ~6 keys orders its edges by (v0, v1) and
// groups the faces of one edge, so no global sort or tree is needed: O(n) plus tiny sorts.
struct HalfEdgeBuckets {
  std::vector<std::size_t> offsets;  // size vertices + 1
  std::vector<std::uint64_t> keys;   // (higher vertex << 32) | face
};

// Faces with an index outside [0, vertex_count) or a repeated index are skipped: they have no
// edges or area, and skipping them keeps every later access in range whatever the input.
bool isUsableFace(const Eigen::Vector3i& f, std::size_t vertex_count) {
  for (int c = 0; c < 3; ++c) {
    if (f[c] < 0 || static_cast<std::size_t>(f[c]) >= vertex_count) {
      return false;
    }
  }
  return f[0] != f[1] && f[1] != f[2] && f[0] != f[2];
}

std::vector<char> usableFaces(const Triangles& faces, std::size_t vertex_count) {
  std::vector<char> usable(faces.size());
  // Face numbers must fit the 32 bits of a half-edge key and the int of MeshEdge.
  const std::size_t kMaxFaces = static_cast<std::size_t>(std::numeric_limits<int>::max());
  for (std::size_t i = 0; i < faces.size() && i < kMaxFaces; ++i) {
    usable[i] = isUsableFace(faces[i], vertex_count) ? 1 : 0;
  }
  return usable;
}

std::size_t index(int i) {
  return static_cast<std::size_t>(i);
}

// Turns counts stored at offsets[v + 1] into CSR offsets.
void prefixSum(std::vector<std::size_t>& offsets) {
  for (std::size_t i = 1; i < offsets.size(); ++i) {
    offsets[i] += offsets[i - 1];
  }
}

void buildVertexFaces(const Triangles& faces,
                      const std::vector<char>& usable,
                      MeshAdjacency& adjacency) {
  auto& offsets = adjacency.vertex_face_offsets;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (int c = 0; c < 3 && usable[i]; ++c) {
      ++offsets[index(faces[i][c]) + 1];
    }
  }
  prefixSum(offsets);
  adjacency.vertex_faces.resize(offsets.back());
  std::vector<std::size_t> cursor(offsets.begin(), offsets.end() - 1);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (int c = 0; c < 3 && usable[i]; ++c) {
      adjacency.vertex_faces[cursor[index(faces[i][c])]++] = static_cast<int>(i);
    }
  }
}

HalfEdgeBuckets bucketHalfEdges(const Triangles& faces,
                                const std::vector<char>& usable,
                                std::size_t vertex_count) {
  HalfEdgeBuckets buckets;
  buckets.offsets.assign(vertex_count + 1, 0);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (int c = 0; c < 3 && usable[i]; ++c) {
      ++buckets.offsets[index(std::min(faces[i][c], faces[i][(c + 1) % 3])) + 1];
    }
  }
  prefixSum(buckets.offsets);
  buckets.keys.resize(buckets.offsets.back());
  std::vector<std::size_t> cursor(buckets.offsets.begin(), buckets.offsets.end() - 1);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (int c = 0; c < 3 && usable[i]; ++c) {
      const int a = faces[i][c];
      const int b = faces[i][(c + 1) % 3];
      const auto hi = static_cast<std::uint64_t>(std::max(a, b));
      buckets.keys[cursor[index(std::min(a, b))]++] = (hi << 32) | static_cast<std::uint64_t>(i);
    }
  }
  return buckets;
}

int higherVertex(std::uint64_t key) {
  return static_cast<int>(key >> 32);
}
int faceOf(std::uint64_t key) {
  return static_cast<int>(key & 0xffffffffu);
}

// One edge from the run keys[first, last) of half-edges between v0 and the same higher vertex.
void appendEdge(int v0,
                const std::vector<std::uint64_t>& keys,
                std::size_t first,
                std::size_t last,
                MeshAdjacency& adjacency) {
  MeshEdge edge;
  edge.v0 = v0;
  edge.v1 = higherVertex(keys[first]);
  edge.f0 = faceOf(keys[first]);
  edge.f1 = last - first > 1 ? faceOf(keys[first + 1]) : -1;
  if (last - first == 1) {
    adjacency.boundary_vertex[index(edge.v0)] = true;
    adjacency.boundary_vertex[index(edge.v1)] = true;
  } else if (last - first > 2) {
    ++adjacency.non_manifold_edges;
  }
  adjacency.edges.push_back(edge);
}

void collectEdges(HalfEdgeBuckets& buckets, MeshAdjacency& adjacency) {
  adjacency.edges.reserve(buckets.keys.size() / 2 + 1);
  for (std::size_t v = 0; v + 1 < buckets.offsets.size(); ++v) {
    const auto begin = buckets.keys.begin() + static_cast<std::ptrdiff_t>(buckets.offsets[v]);
    const auto end = buckets.keys.begin() + static_cast<std::ptrdiff_t>(buckets.offsets[v + 1]);
    std::sort(begin, end);
    std::size_t first = buckets.offsets[v];
    while (first < buckets.offsets[v + 1]) {
      std::size_t last = first + 1;
      while (last < buckets.offsets[v + 1] &&
             higherVertex(buckets.keys[last]) == higherVertex(buckets.keys[first])) {
        ++last;
      }
      appendEdge(static_cast<int>(v), buckets.keys, first, last, adjacency);
      first = last;
    }
  }
}

// Edges are sorted by (v0, v1), so for each vertex the lower neighbours (edges ending at it)
// arrive before the higher ones (edges starting at it), each group ascending: the one-ring lists
// come out sorted without a sort.
void buildNeighbours(MeshAdjacency& adjacency) {
  auto& offsets = adjacency.vertex_neighbour_offsets;
  for (const auto& e : adjacency.edges) {
    ++offsets[index(e.v0) + 1];
    ++offsets[index(e.v1) + 1];
  }
  prefixSum(offsets);
  adjacency.vertex_neighbours.resize(offsets.back());
  std::vector<std::size_t> cursor(offsets.begin(), offsets.end() - 1);
  for (const auto& e : adjacency.edges) {
    adjacency.vertex_neighbours[cursor[index(e.v0)]++] = e.v1;
    adjacency.vertex_neighbours[cursor[index(e.v1)]++] = e.v0;
  }
}

}  // namespace

MeshAdjacency buildMeshAdjacency(const Triangles& faces, std::size_t vertex_count) {
  MeshAdjacency adjacency;
  adjacency.vertex_face_offsets.assign(vertex_count + 1, 0);
  adjacency.vertex_neighbour_offsets.assign(vertex_count + 1, 0);
  adjacency.boundary_vertex.assign(vertex_count, false);
  const std::vector<char> usable = usableFaces(faces, vertex_count);
  buildVertexFaces(faces, usable, adjacency);
  HalfEdgeBuckets buckets = bucketHalfEdges(faces, usable, vertex_count);
  collectEdges(buckets, adjacency);
  buildNeighbours(adjacency);
  return adjacency;
}

}  // namespace freeform_inspection
