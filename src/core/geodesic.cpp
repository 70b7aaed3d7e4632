// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/geodesic.h"

#include <limits>

namespace freeform_inspection {

GeodesicBallGrower::GeodesicBallGrower(const SurfaceGraph& graph)
    : graph_(graph), distance_(graph.size(), std::numeric_limits<double>::infinity()) {}

const std::vector<BallMember>& GeodesicBallGrower::grow(int source, double radius) {
  for (const int cell : touched_) {
    distance_[static_cast<std::size_t>(cell)] = std::numeric_limits<double>::infinity();
  }
  touched_.clear();
  ball_.clear();
  distance_[static_cast<std::size_t>(source)] = 0.0;
  touched_.push_back(source);
  queue_.emplace(0.0, source);
  while (!queue_.empty()) {
    const auto [d, cell] = queue_.top();
    queue_.pop();
    const auto c = static_cast<std::size_t>(cell);
    if (d > distance_[c]) {
      continue;  // a stale entry: the cell was reached by a shorter path since
    }
    ball_.push_back({cell, d});
    for (std::size_t e = graph_.offsets[c]; e < graph_.offsets[c + 1]; ++e) {
      const int next = graph_.neighbours[e];
      const double through = d + graph_.lengths[e];
      auto& known = distance_[static_cast<std::size_t>(next)];
      if (through <= radius && through < known) {
        if (known == std::numeric_limits<double>::infinity()) {
          touched_.push_back(next);
        }
        known = through;
        queue_.emplace(through, next);
      }
    }
  }
  return ball_;
}

}  // namespace freeform_inspection
