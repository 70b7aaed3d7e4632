// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

// Internal to the core library: the k-nearest-neighbour table of a cloud, computed once and
// shared by the cloud curvature (PCA normals, orientation, shape-operator fit, area) and the
// cloud surface edges. Not installed; the public entry points (computeCloudCurvature,
// cloudEdges) build their own table and give the same results.

#include <cstddef>
#include <vector>

#include "large_buffer_internal.h"

#include "freeform_inspection/curvature.h"
#include "freeform_inspection/point_index.h"
#include "freeform_inspection/surface_graph.h"
#include "freeform_inspection/types.h"

namespace freeform_inspection {
namespace internal {

/// The k nearest points of every point of a set among the set itself, row-major (point i's at
/// [i·k, (i+1)·k)), nearest first, exact ties by lower index, the point itself included: row i
/// equals PointIndex(points).nearest(points[i], k). k is clamped to the number of points.
struct NeighbourTable {
  int k = 0;
  LargeVector<int> indices;

  const int* of(std::size_t point) const { return indices.data() + point * std::size_t(k); }
};

/// @brief The table for all points (which must be finite; an empty set gives k = 0).
/// Parallel (OpenMP), each row written by one thread: the same for any thread count. `index`, a
/// PointIndex over the same points that the caller needs anyway, answers the rows the grid
/// cannot prove exact instead of a kd-tree built here (the same rows either way).
NeighbourTable nearestNeighbourTable(const Points& points,
                                     int k,
                                     const PointIndex* index = nullptr);

/// @brief Median distance from a point to its `column`-th nearest neighbour (1: the nearest
/// other) over every 7th point: the cloud's spacing at that rank. 0 when the table has no
/// such column.
double tableDistance(const Points& points, const NeighbourTable& table, int column);

/// Squared distance summed as x, y, z, exactly as PointIndex reports it.
inline double squaredDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double diff = a[i] - b[i];
    sum += diff * diff;
  }
  return sum;
}

/// @brief computeCloudCurvature() with the neighbourhoods taken from a table computed by the
/// caller, or computed here (k = `table_k`, at least config.neighbours) and handed back in
/// `table`, so the caller can reuse it. On invalid input the table is left empty.
CurvatureResult computeCloudCurvature(const Points& points,
                                      const Points& normals,
                                      const CloudCurvatureConfig& config,
                                      int table_k,
                                      NeighbourTable* table);

/// @brief Every point moved along its normal onto the least-squares quadric of its first `k`
/// table neighbours (h = a + b·u + c·v + d·u² + e·u·v + f·v² over the tangent plane: a moving
/// least-squares surface of degree 2): the noise averaged out like on the neighbourhood's plane,
/// without the plane's bias of about H·⟨|t|²⟩/2 into every bend. A point whose neighbours span
/// too little of the plane for six coefficients goes onto the plane through their mean.
Points ontoLocalQuadrics(const Points& points,
                         const Points& normals,
                         const NeighbourTable& table,
                         int k);

/// @brief cloudEdges() from a table of the same points (the first `neighbours` + 1 columns are
/// used; the table must have at least that many or all the points). Each edge once as
/// (lower, higher), in no particular order.
std::vector<SurfaceEdge> cloudEdges(const Points& points,
                                    const Points& normals,
                                    const NeighbourTable& table,
                                    int neighbours,
                                    double max_length);

}  // namespace internal
}  // namespace freeform_inspection
