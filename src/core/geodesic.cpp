// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/geodesic.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace freeform_inspection {
namespace {

// Buckets per ball at most (a bucket is one shortest link wide): a graph with a near-zero link,
// two cells with almost the same centroid, falls back to one heap.
constexpr double kMaxBuckets = 4096.0;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

GeodesicBallGrower::GeodesicBallGrower(const SurfaceGraph& graph)
    : graph_(graph), distance_(graph.size(), kInfinity) {
  shortest_link_ = kInfinity;
  for (const double length : graph.lengths) {
    shortest_link_ = std::min(shortest_link_, length);
  }
}

// Relaxes the links of a settled cell; a new tentative distance goes to its bucket (a later
// one when the buckets are a shortest link wide).
void GeodesicBallGrower::relax(double distance, int cell, double radius) {
  const auto c = static_cast<std::size_t>(cell);
  for (std::size_t e = graph_.offsets[c]; e < graph_.offsets[c + 1]; ++e) {
    const int next = graph_.neighbours[e];
    const double through = distance + graph_.lengths[e];
    auto& known = distance_[static_cast<std::size_t>(next)];
    if (through <= radius && through < known) {
      if (known == kInfinity) {
        touched_.push_back(next);
      }
      known = through;
      auto& bucket = buckets_[dial_ ? static_cast<std::size_t>(through / bucket_width_) : 0];
      bucket.emplace_back(through, next);
      if (!dial_) {
        std::push_heap(bucket.begin(), bucket.end(), std::greater<>());
      }
    }
  }
}

// Dial: the bucket's entries are final once the earlier buckets are settled (a link cannot
// lead back into the bucket it starts from), so they are relaxed in the order they came and
// joined to the ball sorted by (distance, cell), as a heap would have popped them.
void GeodesicBallGrower::settleBucket(std::vector<Entry>& bucket, double radius) {
  settled_.clear();
  for (std::size_t i = 0; i < bucket.size(); ++i) {  // by index: relax may append (rounding)
    const auto [d, cell] = bucket[i];
    if (d > distance_[static_cast<std::size_t>(cell)]) {
      continue;  // a stale entry: the cell was reached by a shorter path since
    }
    settled_.emplace_back(d, cell);
    relax(d, cell, radius);
  }
  bucket.clear();
  std::sort(settled_.begin(), settled_.end());
  for (const auto& [d, cell] : settled_) {
    ball_.push_back({cell, d});
  }
}

void GeodesicBallGrower::settleHeap(std::vector<Entry>& heap, double radius) {
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), std::greater<>());
    const auto [d, cell] = heap.back();
    heap.pop_back();
    if (d > distance_[static_cast<std::size_t>(cell)]) {
      continue;  // stale
    }
    ball_.push_back({cell, d});
    relax(d, cell, radius);
  }
}

const std::vector<BallMember>& GeodesicBallGrower::grow(int source, double radius) {
  for (const int cell : touched_) {
    distance_[static_cast<std::size_t>(cell)] = kInfinity;
  }
  touched_.clear();
  ball_.clear();
  dial_ = shortest_link_ > 0.0 && std::isfinite(radius) && radius / shortest_link_ < kMaxBuckets;
  bucket_width_ = dial_ ? shortest_link_ : 1.0;
  const std::size_t bucket_count = dial_ ? static_cast<std::size_t>(radius / bucket_width_) + 2 : 1;
  if (buckets_.size() < bucket_count) {
    buckets_.resize(bucket_count);
  }
  distance_[static_cast<std::size_t>(source)] = 0.0;
  touched_.push_back(source);
  buckets_[0].emplace_back(0.0, source);
  for (std::size_t b = 0; b < bucket_count; ++b) {
    if (dial_) {
      settleBucket(buckets_[b], radius);
    } else {
      settleHeap(buckets_[b], radius);
    }
  }
  return ball_;
}

}  // namespace freeform_inspection
