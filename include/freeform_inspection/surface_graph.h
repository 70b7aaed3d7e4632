// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "freeform_inspection/types.h"

/// @file surface_graph.h
/// The surface at the resolution the descriptors need. Points are grouped into cells of size h
/// (a fraction of the smallest kernel radius) that are also connected on the surface, so the two
/// sides of a thin wall never share a cell; cells carry the area-weighted curvature of their
/// points, and cells joined by a surface edge are graph neighbours. Geodesic balls are grown on
/// this graph: their cost depends on the surface area and the kernel radius, not on how densely
/// the scanner sampled.

namespace freeform_inspection {

/// An undirected surface edge between two points (mesh edge or accepted kNN pair).
using SurfaceEdge = std::pair<int, int>;

/// Point-level input of the graph.
struct SurfaceSamples {
  const Points* points = nullptr;                  ///< [m]
  const Points* normals = nullptr;                 ///< unit, outward (zero where unknown)
  const std::vector<double>* area = nullptr;       ///< [m^2] per point
  const std::vector<double>* curvature = nullptr;  ///< [1/m] mean curvature per point
  /// Where each point falls into a cell, when not at `points` (a noisy cloud's points moved
  /// onto their fitted planes, so the noise does not spread one surface over several layers of
  /// cells); centroids stay the area-weighted means of `points`.
  const Points* cell_points = nullptr;
};

/// Cells and their adjacency (CSR).
struct SurfaceGraph {
  Points centroids;                  ///< [m] area-weighted cell centres
  Points normals;                    ///< unit area-weighted cell normals
  std::vector<double> area;          ///< [m^2] per cell
  std::vector<double> curvature;     ///< [1/m] area-weighted mean curvature per cell
  std::vector<int> point_cell;       ///< cell of every point (-1 for points with no area)
  std::vector<std::size_t> offsets;  ///< CSR: neighbours of cell c are [offsets[c], offsets[c+1])
  std::vector<int> neighbours;       ///< neighbour cells
  std::vector<double> lengths;       ///< [m] centroid distance to each neighbour

  std::size_t size() const { return centroids.size(); }
};

/// @brief Groups points into connected cells of size `cell_size` and links adjacent cells.
/// @param edges surface edges between points (each once, either direction).
SurfaceGraph buildSurfaceGraph(const SurfaceSamples& samples,
                               const std::vector<SurfaceEdge>& edges,
                               double cell_size);

/// @brief Voxel of every point on a grid of `cell_size` anchored at the points' bounding box:
/// equal keys mean the same voxel. Points must be finite.
std::vector<std::uint64_t> voxelKeys(const Points& points, double cell_size);

/// @brief Undirected edges of a triangle mesh, each once.
std::vector<SurfaceEdge> meshEdges(const Triangles& faces);

/// @brief Surface edges of a cloud: each point to its `neighbours` nearest points within
/// `max_length`, kept only when both normals face the same side (n_i·n_j > 0), so points on the
/// two sides of a thin wall are not joined.
std::vector<SurfaceEdge> cloudEdges(const Points& points,
                                    const Points& normals,
                                    int neighbours,
                                    double max_length);

}  // namespace freeform_inspection
