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
    : offsets_(graph.offsets), distance_(graph.size(), kInfinity), settled_(graph.size(), 0) {
  links_.reserve(graph.neighbours.size());
  shortest_link_ = kInfinity;
  for (std::size_t e = 0; e < graph.neighbours.size(); ++e) {
    links_.push_back({graph.neighbours[e], graph.lengths[e]});
    shortest_link_ = std::min(shortest_link_, graph.lengths[e]);
  }
  // Each cell's links shortest first, so relax() stops at the first that leaves the ball. The
  // order of the links changes no distance, and each bucket is sorted before it joins the ball.
  for (std::size_t c = 0; c + 1 < offsets_.size(); ++c) {
    std::sort(links_.begin() + static_cast<std::ptrdiff_t>(offsets_[c]),
              links_.begin() + static_cast<std::ptrdiff_t>(offsets_[c + 1]),
              [](const Link& a, const Link& b) {
                return a.length < b.length || (a.length == b.length && a.to < b.to);
              });
  }
}

// Relaxes the links of a settled cell; a new tentative distance goes to its bucket (a later
// one when the buckets are a shortest link wide).
void GeodesicBallGrower::relax(double distance, int cell, double radius) {
  const auto c = static_cast<std::size_t>(cell);
  const Link* const end = links_.data() + offsets_[c + 1];
  for (const Link* link = links_.data() + offsets_[c]; link != end; ++link) {
    const double through = distance + link->length;
    if (!(through <= radius)) {
      break;  // and so are the longer links after it
    }
    auto& known = distance_[static_cast<std::size_t>(link->to)];
    if (through < known) {
      known = through;
      auto& bucket = buckets_[dial_ ? static_cast<std::size_t>(through * buckets_per_metre_) : 0];
      bucket.emplace_back(through, link->to);
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
  bucket_settled_.clear();
  for (std::size_t i = 0; i < bucket.size(); ++i) {  // by index: relax may append (rounding)
    const auto [d, cell] = bucket[i];
    const auto c = static_cast<std::size_t>(cell);
    // A stale entry (the cell was reached by a shorter path since), or a cell already settled
    // that a rounding at the bucket's edge improved by an ulp: never joins the ball twice.
    if (d > distance_[c] || settled_[c] != 0) {
      continue;
    }
    settled_[c] = 1;
    bucket_settled_.emplace_back(d, cell);
    relax(d, cell, radius);
  }
  bucket.clear();
  std::sort(bucket_settled_.begin(), bucket_settled_.end());
  for (const auto& [d, cell] : bucket_settled_) {
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
  // Every cell given a distance is settled, so the last ball's members are all there is to reset.
  for (const BallMember& member : ball_) {
    distance_[static_cast<std::size_t>(member.cell)] = kInfinity;
    settled_[static_cast<std::size_t>(member.cell)] = 0;
  }
  ball_.clear();
  dial_ = shortest_link_ > 0.0 && std::isfinite(radius) && radius / shortest_link_ < kMaxBuckets;
  buckets_per_metre_ = dial_ ? 1.0 / shortest_link_ : 0.0;
  const std::size_t bucket_count =
      dial_ ? static_cast<std::size_t>(radius * buckets_per_metre_) + 2 : 1;
  if (buckets_.size() < bucket_count) {
    buckets_.resize(bucket_count);
  }
  distance_[static_cast<std::size_t>(source)] = 0.0;
  buckets_[0].emplace_back(0.0, source);
  for (std::size_t b = 0; b < bucket_count; ++b) {
    if (buckets_[b].empty()) {
      continue;  // most are: a bucket is one shortest link wide
    }
    if (dial_) {
      settleBucket(buckets_[b], radius);
    } else {
      settleHeap(buckets_[b], radius);
    }
  }
  return ball_;
}

}  // namespace freeform_inspection
