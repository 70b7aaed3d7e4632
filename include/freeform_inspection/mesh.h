// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>

#include "freeform_inspection/types.h"

/// @file mesh.h
/// Mesh construction helpers and topology checks shared by the loaders and the model.

namespace freeform_inspection {

/// @brief Bounding box of a point set.
/// @return a zero box for an empty set.
BoundingBox computeBoundingBox(const Points& points);

/// @brief How thin a part is: the extent of the vertices along the axis in which the surface
/// spreads least (the smallest principal axis of the surface's second moments) [m]. A
/// 100 × 20 × 10 mm bar in any pose: 10 mm. 0 for a mesh without area.
double principalThickness(const TriangleMesh& mesh);

/// @brief Area of one triangle; its indices must be in range.
double triangleArea(const Points& vertices, const Eigen::Vector3i& face);

/// @brief Unit face normals from the vertex order (right-hand rule); zero for degenerate faces.
Points computeFaceNormals(const Points& vertices, const Triangles& faces);

/// @brief Builds a welded mesh from a triangle soup (three corners per triangle, as STL stores).
/// Corners with bit-identical coordinates become one vertex; faces whose corners collapse onto
/// fewer than three distinct vertices are dropped. Face normals are computed.
/// @param corners 3·n positions, triangle i uses corners 3i, 3i+1, 3i+2.
TriangleMesh weldTriangleSoup(const Points& corners);

/// @brief Splits every edge longer than `max_edge` at its midpoint, repeatedly, and
/// re-triangulates each face by how many of its edges were split (red–green refinement: shared
/// edges split once, so the result stays conforming, without T-junctions). Orientation is kept.
/// Stops early rather than exceed `max_faces`. Face normals are recomputed.
TriangleMesh refineLongEdges(const TriangleMesh& mesh, double max_edge, std::size_t max_faces);

/// Edge and volume facts about a mesh, enough to tell a closed, oriented solid from the rest.
struct MeshTopology {
  std::size_t edges = 0;               ///< distinct undirected edges
  std::size_t boundary_edges = 0;      ///< edges used by one face
  std::size_t non_manifold_edges = 0;  ///< edges used by three or more faces
  std::size_t misoriented_edges = 0;   ///< two-face edges traversed the same way by both faces
  std::size_t degenerate_faces = 0;    ///< faces with a repeated index or zero area
  std::size_t unused_vertices = 0;     ///< vertices no face references
  double signed_volume = 0.0;          ///< [m^3] positive when faces wind outward
  double area = 0.0;                   ///< [m^2] total surface area

  /// Closed two-manifold with consistent orientation.
  bool isClosedManifold() const {
    return boundary_edges == 0 && non_manifold_edges == 0 && misoriented_edges == 0;
  }
  /// Closed, consistently oriented and enclosing positive volume (normals point out).
  bool isOutwardSolid() const { return isClosedManifold() && signed_volume > 0.0; }
};

/// @brief Counts boundary, non-manifold and misoriented edges and computes volume and area.
/// Face indices must be in range (the loaders guarantee it). Only exactly zero-area faces count
/// as degenerate: slivers are a quality question, not a topological one.
MeshTopology analyzeTopology(const TriangleMesh& mesh);

}  // namespace freeform_inspection
