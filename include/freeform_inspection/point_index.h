// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <memory>
#include <vector>

#include "freeform_inspection/types.h"

/// @file point_index.h
/// Nearest-neighbour queries on a fixed point set (a kd-tree; nanoflann behind the curtain).

namespace freeform_inspection {

/// One neighbour: its index in the indexed set and its squared distance.
struct Neighbour {
  int index = -1;                 ///< index into the points the index was built on
  double squared_distance = 0.0;  ///< [m^2]
};

/// A kd-tree over a point set. The points are copied; queries are thread-safe.
class PointIndex {
 public:
  explicit PointIndex(const Points& points);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  /// The k nearest points (fewer if the set is smaller), nearest first; includes the query
  /// point itself when it is in the set.
  std::vector<Neighbour> nearest(const Eigen::Vector3d& query, int k) const;

  /// The nearest point of every query, each exactly nearest(query, 1).front() (index -1 for a
  /// non-finite query or an empty set). Parallel; the queries are answered in a space-filling
  /// order, so consecutive searches walk the same branches of the tree.
  std::vector<Neighbour> nearestEach(const Points& queries) const;

  /// All points within `radius` [m], nearest first (ties by index).
  std::vector<Neighbour> within(const Eigen::Vector3d& query, double radius) const;

  /// About `count` of the points within `radius`, spread from the nearest to the farthest:
  /// every s-th of within(query, radius), s = max(1, n / count) for its n points (so up to
  /// 2·count − 1 of them), in that order. A sample of a wide ball without a Neighbour for each
  /// of its points.
  std::vector<Neighbour> spreadWithin(const Eigen::Vector3d& query,
                                      double radius,
                                      std::size_t count) const;

  /// How many points within(query, radius) would return, without gathering or sorting them.
  std::size_t countWithin(const Eigen::Vector3d& query, double radius) const;

  std::size_t size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// @brief Median distance from a point to its nearest other point, over an even sample of at
/// most `samples` of the indexed `points`: the sampling spacing of a scan [m]. 0 for < 2 points.
double medianSpacing(const Points& points, const PointIndex& index, std::size_t samples = 2000);

}  // namespace freeform_inspection
