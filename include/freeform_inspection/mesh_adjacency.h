// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <vector>

#include "freeform_inspection/types.h"

/// @file mesh_adjacency.h
/// One-ring connectivity of a triangle mesh (paper §3.1): vertex → faces, vertex → vertices,
/// edges with their two faces, boundary detection. Compressed (CSR) arrays, built in O(n log n)
/// so that a 1M-vertex mesh takes well under a second.

namespace freeform_inspection {

/// An undirected edge and the faces on each side.
struct MeshEdge {
  int v0 = -1;  ///< lower vertex index
  int v1 = -1;  ///< higher vertex index
  int f0 = -1;  ///< a face using the edge
  int f1 = -1;  ///< the other face, -1 on a boundary (or the 2nd of several on non-manifold edges)
};

/// Connectivity of a mesh. Index ranges use CSR offsets: the faces around vertex v are
/// vertex_faces[vertex_face_offsets[v] .. vertex_face_offsets[v+1]).
struct MeshAdjacency {
  std::vector<std::size_t> vertex_face_offsets;       ///< size vertices + 1
  std::vector<int> vertex_faces;                      ///< faces around each vertex
  std::vector<std::size_t> vertex_neighbour_offsets;  ///< size vertices + 1
  std::vector<int> vertex_neighbours;                 ///< one-ring vertices, ascending per vertex
  std::vector<MeshEdge> edges;                        ///< every undirected edge once, sorted
  std::vector<bool> boundary_vertex;                  ///< vertex touches a boundary edge
  std::size_t non_manifold_edges = 0;                 ///< edges used by 3+ faces (kept, flagged)
};

/// @brief Builds the connectivity. Faces must index into [0, vertex_count).
MeshAdjacency buildMeshAdjacency(const Triangles& faces, std::size_t vertex_count);

}  // namespace freeform_inspection
