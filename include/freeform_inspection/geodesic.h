// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <queue>
#include <utility>
#include <vector>

#include "freeform_inspection/surface_graph.h"

/// @file geodesic.h
/// Geodesic balls on the surface graph (paper §3.2: the extended neighbourhood of a vertex,
/// every member with its geodesic distance). Shortest paths along cell-centroid edges (Dijkstra)
/// stand in for the paper's fast marching: on the cell graph the path length overestimates the
/// true geodesic by a few percent, the same on the CAD and on the scan.

namespace freeform_inspection {

/// A cell of a ball and its geodesic distance from the centre.
struct BallMember {
  int cell = -1;
  double distance = 0.0;  ///< [m]
};

/// Reusable scratch space for growing balls on one graph (one per thread).
class GeodesicBallGrower {
 public:
  explicit GeodesicBallGrower(const SurfaceGraph& graph);

  /// @brief Every cell within geodesic distance `radius` of `source`, nearest first (ties by
  /// cell index, so the order is deterministic). The source itself comes first at distance 0.
  const std::vector<BallMember>& grow(int source, double radius);

 private:
  using Entry = std::pair<double, int>;
  const SurfaceGraph& graph_;
  std::vector<double> distance_;
  std::vector<int> touched_;
  std::vector<BallMember> ball_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue_;
};

}  // namespace freeform_inspection
