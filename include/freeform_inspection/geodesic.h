// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

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
///
/// Dijkstra with buckets as wide as the graph's shortest link (Dial's queue): no cell can improve
/// another of its own bucket, so a bucket is settled in any order and then sorted, instead of
/// every cell passing through a heap of the whole front. The ball is exactly a binary heap's.
/// A graph whose shortest link would need too many buckets uses one heap, as before.
class GeodesicBallGrower {
 public:
  explicit GeodesicBallGrower(const SurfaceGraph& graph);

  /// @brief Every cell within geodesic distance `radius` of `source`, nearest first (ties by
  /// cell index, so the order is deterministic). The source itself comes first at distance 0.
  const std::vector<BallMember>& grow(int source, double radius);

 private:
  using Entry = std::pair<double, int>;
  void relax(double distance, int cell, double radius);
  void settleBucket(std::vector<Entry>& bucket, double radius);
  void settleHeap(std::vector<Entry>& heap, double radius);

  struct Link {
    int to;
    double length;  ///< [m]
  };

  std::vector<std::size_t> offsets_;  ///< the graph's CSR, with each link's target and length
  std::vector<Link> links_;           ///< side by side: one cache line per cell's links
  double shortest_link_ = 0.0;        ///< [m]
  bool dial_ = false;                 ///< whether the current ball uses one bucket per link
  double buckets_per_metre_ = 1.0;    ///< of the current ball
  std::vector<double> distance_;
  std::vector<char> settled_;  ///< per cell, in the current ball
  std::vector<BallMember> ball_;
  std::vector<std::vector<Entry>> buckets_;
  std::vector<Entry> bucket_settled_;
};

}  // namespace freeform_inspection
