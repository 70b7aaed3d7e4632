// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/point_index.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include <nanoflann.hpp>

namespace freeform_inspection {
namespace {

// nanoflann reads coordinates through this adaptor, so the tree needs no copy in its own layout.
struct PointsAdaptor {
  const Points* points = nullptr;

  std::size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(std::size_t index, std::size_t dim) const {
    return (*points)[index][static_cast<Eigen::Index>(dim)];
  }
  template <class BoundingBoxT>
  bool kdtree_get_bbox(BoundingBoxT& /*box*/) const {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<
    nanoflann::L2_Simple_Adaptor<double, PointsAdaptor, double, std::uint32_t>,
    PointsAdaptor,
    3,
    std::uint32_t>;

constexpr std::size_t kLeafSize = 10;

// Same summation order as nanoflann's L2_Simple_Adaptor, so reported distances are exactly the
// ones the tree compared (and a brute-force search written the same way agrees bit for bit).
double squaredDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double diff = a[i] - b[i];
    sum += diff * diff;
  }
  return sum;
}

bool closerThan(double distance_a,
                std::uint32_t index_a,
                double distance_b,
                std::uint32_t index_b) {
  return distance_a < distance_b || (distance_a == distance_b && index_a < index_b);
}

// k-nearest result set with a deterministic tie rule (equal distances: lower index wins).
// nanoflann's own KNNResultSet keeps whichever tie it meets first, which depends on the tree
// layout; regular grids are full of exact ties, and neighbourhoods should not depend on it.
class OrderedKnnResult {
 public:
  explicit OrderedKnnResult(std::size_t capacity) : capacity_(capacity) {
    entries_.reserve(capacity + 1);
  }

  std::size_t size() const { return entries_.size(); }
  bool full() const { return entries_.size() == capacity_; }

  // The tree only offers points strictly closer than this; nudging it up lets exact ties in.
  double worstDist() const {
    if (!full()) {
      return std::numeric_limits<double>::max();
    }
    return std::nextafter(entries_.back().first, std::numeric_limits<double>::infinity());
  }

  bool addPoint(double distance, std::uint32_t index) {
    if (full() && !closerThan(distance, index, entries_.back().first, entries_.back().second)) {
      return true;
    }
    const auto position = std::find_if(entries_.begin(), entries_.end(), [&](const auto& entry) {
      return closerThan(distance, index, entry.first, entry.second);
    });
    entries_.insert(position, {distance, index});
    if (entries_.size() > capacity_) {
      entries_.pop_back();
    }
    return true;
  }

  const std::vector<std::pair<double, std::uint32_t>>& entries() const { return entries_; }

 private:
  std::size_t capacity_;
  std::vector<std::pair<double, std::uint32_t>> entries_;
};

}  // namespace

// Only finite points enter the tree (a NaN would poison its bounding boxes); `original` maps the
// tree's indices back to the caller's, so non-finite points are simply never returned.
struct PointIndex::Impl {
  Points points;
  std::vector<int> original;
  std::size_t input_size = 0;
  PointsAdaptor adaptor;
  std::unique_ptr<KdTree> tree;

  Neighbour neighbour(const Eigen::Vector3d& query, std::uint32_t index) const {
    return Neighbour{original[index], squaredDistance(query, points[index])};
  }
};

PointIndex::PointIndex(const Points& points) : impl_(std::make_unique<Impl>()) {
  impl_->input_size = points.size();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].allFinite()) {
      impl_->points.push_back(points[i]);
      impl_->original.push_back(static_cast<int>(i));
    }
  }
  impl_->adaptor.points = &impl_->points;
  impl_->tree = std::make_unique<KdTree>(
      3, impl_->adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize));
}

PointIndex::~PointIndex() = default;

std::vector<Neighbour> PointIndex::nearest(const Eigen::Vector3d& query, int k) const {
  std::vector<Neighbour> result;
  if (k <= 0 || impl_->points.empty() || !query.allFinite()) {
    return result;
  }
  OrderedKnnResult found(std::min(static_cast<std::size_t>(k), impl_->points.size()));
  impl_->tree->findNeighbors(found, query.data(), nanoflann::SearchParams());
  result.reserve(found.size());
  for (const auto& entry : found.entries()) {
    result.push_back(impl_->neighbour(query, entry.second));
  }
  return result;
}

std::vector<Neighbour> PointIndex::within(const Eigen::Vector3d& query, double radius) const {
  std::vector<Neighbour> result;
  if (!(radius >= 0.0) || impl_->points.empty() || !query.allFinite()) {
    return result;
  }
  const double squared_radius = radius * radius;
  // nanoflann keeps distances strictly below its radius; the nudge makes `within` inclusive.
  const double search_radius =
      std::nextafter(squared_radius, std::numeric_limits<double>::infinity());
  std::vector<std::pair<std::uint32_t, double>> found;
  impl_->tree->radiusSearch(query.data(), search_radius, found, nanoflann::SearchParams());
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
    return closerThan(a.second, a.first, b.second, b.first);
  });
  result.reserve(found.size());
  for (const auto& entry : found) {
    result.push_back(impl_->neighbour(query, entry.first));
  }
  return result;
}

std::size_t PointIndex::size() const {
  return impl_->input_size;
}

}  // namespace freeform_inspection
