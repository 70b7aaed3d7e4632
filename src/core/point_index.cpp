// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/point_index.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>

#include "cloud_neighbours_internal.h"
#include "median_internal.h"
#include <Eigen/Geometry>
#include <nanoflann.hpp>
#include <parallel/algorithm>

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
using internal::squaredDistance;

bool closerThan(double distance_a,
                std::uint32_t index_a,
                double distance_b,
                std::uint32_t index_b) {
  return distance_a < distance_b || (distance_a == distance_b && index_a < index_b);
}

// k-nearest result set with a deterministic tie rule (equal distances: lower index wins).
// nanoflann's own KNNResultSet keeps whichever tie it meets first, which depends on the tree
// layout; regular grids are full of exact ties, and neighbourhoods should not depend on it.
// The buffers are the caller's (reset() between queries), so a batch of queries allocates
// nothing; the bound the tree asks for at every node is cached, not recomputed.
class OrderedKnnResult {
 public:
  OrderedKnnResult(std::size_t capacity, double* distances, std::uint32_t* indices)
      : capacity_(capacity), distances_(distances), indices_(indices) {}

  void reset() {
    count_ = 0;
    worst_ = std::numeric_limits<double>::max();
  }

  std::size_t size() const { return count_; }
  bool full() const { return count_ == capacity_; }

  // The tree only offers points strictly closer than this; nudging it up lets exact ties in.
  double worstDist() const { return worst_; }

  bool addPoint(double distance, std::uint32_t index) {
    if (full() && !closerThan(distance, index, distances_[count_ - 1], indices_[count_ - 1])) {
      return true;
    }
    std::size_t i = full() ? count_ - 1 : count_++;  // the slot to fill, moving larger ones up
    for (; i > 0 && closerThan(distance, index, distances_[i - 1], indices_[i - 1]); --i) {
      distances_[i] = distances_[i - 1];
      indices_[i] = indices_[i - 1];
    }
    distances_[i] = distance;
    indices_[i] = index;
    if (full()) {
      worst_ = std::nextafter(distances_[count_ - 1], std::numeric_limits<double>::infinity());
    }
    return true;
  }

  std::uint32_t index(std::size_t i) const { return indices_[i]; }

 private:
  std::size_t capacity_;
  double* distances_;
  std::uint32_t* indices_;
  std::size_t count_ = 0;
  double worst_ = std::numeric_limits<double>::max();
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

  // Tree indices and squared distances of the points within `radius`, nearest first.
  std::vector<std::pair<std::uint32_t, double>> withinNearestFirst(const Eigen::Vector3d& query,
                                                                   double radius) const;
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
  const std::size_t capacity = std::min(static_cast<std::size_t>(k), impl_->points.size());
  std::vector<double> distances(capacity);
  std::vector<std::uint32_t> indices(capacity);
  OrderedKnnResult found(capacity, distances.data(), indices.data());
  impl_->tree->findNeighbors(found, query.data(), nanoflann::SearchParams());
  result.reserve(found.size());
  for (std::size_t i = 0; i < found.size(); ++i) {
    result.push_back(impl_->neighbour(query, found.index(i)));
  }
  return result;
}

namespace {

// Morton code of a point's position in `box` on a 1024³ lattice: nearby points get nearby codes.
std::uint32_t mortonCode(const Eigen::Vector3d& p, const Eigen::AlignedBox3d& box) {
  const Eigen::Vector3d extent = box.sizes().cwiseMax(std::numeric_limits<double>::min());
  const Eigen::Vector3d unit = (p - box.min()).cwiseQuotient(extent);
  std::uint32_t code = 0;
  for (int axis = 0; axis < 3; ++axis) {
    auto v = static_cast<std::uint32_t>(std::clamp(unit[axis], 0.0, 1.0) * 1023.0);
    for (int bit = 0; bit < 10; ++bit) {
      code |= ((v >> bit) & 1u) << (3 * bit + axis);
    }
  }
  return code;
}

}  // namespace

std::vector<Neighbour> PointIndex::nearestEach(const Points& queries) const {
  std::vector<Neighbour> result(queries.size());
  if (impl_->points.empty()) {
    return result;
  }
  Eigen::AlignedBox3d box;
  for (const auto& q : queries) {
    if (q.allFinite()) {
      box.extend(q);
    }
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> order;
  order.reserve(queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i) {
    if (queries[i].allFinite()) {
      order.emplace_back(mortonCode(queries[i], box), static_cast<std::uint32_t>(i));
    }
  }
  // Unique pairs: one order for any thread count (the answers do not depend on it anyway).
  __gnu_parallel::sort(order.begin(), order.end());
  const auto count = static_cast<std::ptrdiff_t>(order.size());
#pragma omp parallel
  {
    double distance = 0.0;
    std::uint32_t index = 0;
    OrderedKnnResult found(1, &distance, &index);
#pragma omp for schedule(static)
    for (std::ptrdiff_t o = 0; o < count; ++o) {
      const std::uint32_t q = order[static_cast<std::size_t>(o)].second;
      found.reset();
      impl_->tree->findNeighbors(found, queries[q].data(), nanoflann::SearchParams());
      result[q] = impl_->neighbour(queries[q], index);
    }
  }
  return result;
}

namespace {

// nanoflann keeps distances strictly below its radius; the nudge makes `within` inclusive.
double inclusiveSquaredRadius(double radius) {
  return std::nextafter(radius * radius, std::numeric_limits<double>::infinity());
}

// A radius search's result set that only counts (nanoflann's result-set interface).
class CountingResult {
 public:
  explicit CountingResult(double squared_radius) : squared_radius_(squared_radius) {}
  std::size_t size() const { return count_; }
  bool full() const { return true; }
  bool addPoint(double distance, std::uint32_t /*index*/) {
    count_ += distance < squared_radius_ ? 1 : 0;
    return true;
  }
  double worstDist() const { return squared_radius_; }

 private:
  double squared_radius_;
  std::size_t count_ = 0;
};

using Found = std::vector<std::pair<std::uint32_t, double>>;  // tree index, squared distance

bool foundCloser(const Found::value_type& a, const Found::value_type& b) {
  return closerThan(a.second, a.first, b.second, b.first);
}

// `found` (squared distances in [0, squared_radius]) nearest first, ties by index: what
// std::sort with foundCloser gives, in linear time. On a surface the points of a ball spread
// evenly over its squared radius (area grows with r²), so as many buckets of equal width in r²
// as points hold about one each; a bucket is sorted by the full rule, and buckets keep the order
// of distance because the bucket number never falls as the distance grows.
void sortNearestFirst(Found& found, double squared_radius) {
  constexpr std::size_t kFewForBuckets = 64;
  const std::size_t count = found.size();
  const double per_bucket = static_cast<double>(count) / squared_radius;
  if (count < kFewForBuckets || !(per_bucket > 0.0) || !std::isfinite(per_bucket)) {
    std::sort(found.begin(), found.end(), foundCloser);
    return;
  }
  // Clamped before the conversion: a distance a nudge past the radius lands in the last bucket.
  const double last = static_cast<double>(count - 1);
  const auto bucket = [&](double squared_distance) {
    return static_cast<std::size_t>(std::min(last, squared_distance * per_bucket));
  };
  std::vector<std::uint32_t> starts(count + 1, 0);
  for (const auto& entry : found) {
    ++starts[bucket(entry.second) + 1];
  }
  std::partial_sum(starts.begin(), starts.end(), starts.begin());
  Found ordered(count);
  std::vector<std::uint32_t> next(starts.begin(), starts.end() - 1);
  for (const auto& entry : found) {
    ordered[next[bucket(entry.second)]++] = entry;
  }
  for (std::size_t b = 0; b < count; ++b) {
    if (starts[b + 1] - starts[b] > 1) {
      std::sort(ordered.begin() + starts[b], ordered.begin() + starts[b + 1], foundCloser);
    }
  }
  found.swap(ordered);
}

}  // namespace

Found PointIndex::Impl::withinNearestFirst(const Eigen::Vector3d& query, double radius) const {
  Found found;
  if (!(radius >= 0.0) || points.empty() || !query.allFinite()) {
    return found;
  }
  const double squared_radius = inclusiveSquaredRadius(radius);
  tree->radiusSearch(query.data(), squared_radius, found, nanoflann::SearchParams(0, 0.0f, false));
  sortNearestFirst(found, squared_radius);
  return found;
}

std::vector<Neighbour> PointIndex::within(const Eigen::Vector3d& query, double radius) const {
  return spreadWithin(query, radius, std::numeric_limits<std::size_t>::max());
}

std::vector<Neighbour> PointIndex::spreadWithin(const Eigen::Vector3d& query,
                                                double radius,
                                                std::size_t count) const {
  const Found found = impl_->withinNearestFirst(query, radius);
  const std::size_t stride =
      std::max<std::size_t>(1, found.size() / std::max<std::size_t>(1, count));
  std::vector<Neighbour> result;
  result.reserve((found.size() + stride - 1) / stride);
  for (std::size_t j = 0; j < found.size(); j += stride) {
    result.push_back(impl_->neighbour(query, found[j].first));
  }
  return result;
}

std::size_t PointIndex::countWithin(const Eigen::Vector3d& query, double radius) const {
  if (!(radius >= 0.0) || impl_->points.empty() || !query.allFinite()) {
    return 0;
  }
  CountingResult counted(inclusiveSquaredRadius(radius));
  impl_->tree->findNeighbors(counted, query.data(), nanoflann::SearchParams());
  return counted.size();
}

std::size_t PointIndex::size() const {
  return impl_->input_size;
}

namespace internal {
namespace {

// Rows for `queries` (positions into `points`) from a kd-tree over all the points: the caller's
// index over the same points when it has one, else one built here.
void kdTreeRows(const Points& points,
                const std::vector<std::uint32_t>& queries,
                const PointIndex* index,
                NeighbourTable& table) {
  const auto width = static_cast<std::size_t>(table.k);
  const auto count = static_cast<std::ptrdiff_t>(queries.size());
  if (index != nullptr) {
#pragma omp parallel for schedule(dynamic, 256)
    for (std::ptrdiff_t q = 0; q < count; ++q) {
      const std::size_t point = queries[static_cast<std::size_t>(q)];
      const std::vector<Neighbour> found = index->nearest(points[point], table.k);
      int* row = table.indices.data() + point * width;
      for (std::size_t j = 0; j < width; ++j) {
        row[j] = found[j].index;
      }
    }
    return;
  }
  PointsAdaptor adaptor{&points};
  const KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize));
#pragma omp parallel
  {
    std::vector<double> distances(width);
    std::vector<std::uint32_t> indices(width);
    OrderedKnnResult found(width, distances.data(), indices.data());
#pragma omp for schedule(dynamic, 256)
    for (std::ptrdiff_t q = 0; q < count; ++q) {
      const std::size_t point = queries[static_cast<std::size_t>(q)];
      found.reset();
      tree.findNeighbors(found, points[point].data(), nanoflann::SearchParams());
      int* row = table.indices.data() + point * width;
      for (std::size_t j = 0; j < width; ++j) {
        row[j] = static_cast<int>(indices[j]);
      }
    }
  }
}

// Rows for a few `queries` by comparing with every point (cheaper than building a tree): the k
// nearest so far kept in a max-heap of (distance, index) pairs, which order as closerThan().
void bruteForceRows(const Points& points,
                    const std::vector<std::uint32_t>& queries,
                    NeighbourTable& table) {
  const auto width = static_cast<std::size_t>(table.k);
  const auto count = static_cast<std::ptrdiff_t>(queries.size());
#pragma omp parallel
  {
    std::vector<std::pair<double, std::uint32_t>> nearest;
    nearest.reserve(width + 1);
#pragma omp for schedule(dynamic, 1)
    for (std::ptrdiff_t q = 0; q < count; ++q) {
      const std::size_t point = queries[static_cast<std::size_t>(q)];
      nearest.clear();
      for (std::size_t j = 0; j < points.size(); ++j) {
        const std::pair<double, std::uint32_t> candidate{squaredDistance(points[point], points[j]),
                                                         static_cast<std::uint32_t>(j)};
        if (nearest.size() < width) {
          nearest.push_back(candidate);
          std::push_heap(nearest.begin(), nearest.end());
        } else if (candidate < nearest.front()) {
          std::pop_heap(nearest.begin(), nearest.end());
          nearest.back() = candidate;
          std::push_heap(nearest.begin(), nearest.end());
        }
      }
      std::sort_heap(nearest.begin(), nearest.end());
      int* row = table.indices.data() + point * width;
      for (std::size_t j = 0; j < width; ++j) {
        row[j] = static_cast<int>(nearest[j].second);
      }
    }
  }
}

// Squared k-th distance of the previous row in a cube × this = the first bound tried.
constexpr double kBoundGrowth = 1.5;

// Misses × points up to which brute force beats building a kd-tree.
constexpr std::size_t kBruteForceWork = std::size_t(1) << 21;

// Below this many points the kd-tree alone is fast enough.
constexpr std::size_t kGridMinimumPoints = 4096;
// Subsampling stride of the cell-size estimate.
constexpr std::size_t kEstimateStride = 16;
// Cube side over the estimated k-th neighbour distance: larger cubes mean more candidates per
// query, smaller ones more rows the 27 cubes cannot prove exact.
constexpr double kCellOverKth = 1.3;

// A uniform grid of cubes of side h over the points, sorted by cube (CSR), with an open-addressing
// hash from cube coordinates to the cube's range of points.
class PointGrid {
 public:
  PointGrid(const Points& points, double cell) : cell_(cell) {
    origin_ = points.front();
    for (const auto& p : points) {
      origin_ = origin_.cwiseMin(p);
    }
    const std::size_t n = points.size();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
    const auto count = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < count; ++i) {
      const auto u = static_cast<std::size_t>(i);
      keyed[u] = {key(coordinates(points[u])), static_cast<std::uint32_t>(u)};
    }
    __gnu_parallel::sort(keyed.begin(), keyed.end());  // unique keys: any thread count agrees
    order_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      order_[i] = keyed[i].second;
      if (i == 0 || keyed[i].first != keyed[i - 1].first) {
        starts_.push_back(static_cast<std::uint32_t>(i));
        keys_.push_back(keyed[i].first);
      }
    }
    // The points copied in cube order: a block of cubes is then read from contiguous memory
    // rather than gathered from all over the cloud, for each of the 27 blocks a point is in.
    sorted_.resize(n);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < count; ++i) {
      sorted_[static_cast<std::size_t>(i)] = points[order_[static_cast<std::size_t>(i)]];
    }
    starts_.push_back(static_cast<std::uint32_t>(n));
    std::size_t capacity = 16;
    hash_shift_ = 60;
    while (capacity < 2 * keys_.size()) {
      capacity *= 2;
      --hash_shift_;
    }
    slots_.assign(capacity, -1);
    for (std::size_t c = 0; c < keys_.size(); ++c) {
      std::size_t slot = hash(keys_[c]);
      while (slots_[slot] >= 0) {
        slot = (slot + 1) & (capacity - 1);
      }
      slots_[slot] = static_cast<std::int64_t>(c);
    }
  }

  std::size_t cubes() const {
    return keys_.size();
  }
  // Points of cube c: order()[starts(c) .. starts(c + 1)).
  std::size_t start(std::size_t c) const {
    return starts_[c];
  }
  const std::vector<std::uint32_t>& order() const {
    return order_;
  }
  // Position of the i-th point in cube order: points[order()[i]].
  const Eigen::Vector3d& position(std::size_t i) const {
    return sorted_[i];
  }
  Eigen::Array3i cubeOf(std::size_t c) const {
    return decode(keys_[c]);
  }

  // Index of the cube at integer coordinates, or -1 when empty.
  std::int64_t find(const Eigen::Array3i& at) const {
    if ((at < 0).any() || (at >= kSpan).any()) {
      return -1;
    }
    const std::uint64_t wanted = key(at);
    for (std::size_t slot = hash(wanted);; slot = (slot + 1) & (slots_.size() - 1)) {
      const std::int64_t c = slots_[slot];
      if (c < 0 || keys_[static_cast<std::size_t>(c)] == wanted) {
        return c;
      }
    }
  }

  // Lower corner of the cube at integer coordinates.
  Eigen::Vector3d corner(const Eigen::Array3i& at) const {
    return origin_ + cell_ * at.cast<double>().matrix();
  }
  double cell() const {
    return cell_;
  }

 private:
  static constexpr int kSpan = 1 << 21;

  Eigen::Array3i coordinates(const Eigen::Vector3d& p) const {
    const Eigen::Array3d c = ((p - origin_) / cell_).array().floor();
    return c.min(double(kSpan - 1)).cast<int>();
  }
  static std::uint64_t key(const Eigen::Array3i& c) {
    return (std::uint64_t(c.x()) << 42) | (std::uint64_t(c.y()) << 21) | std::uint64_t(c.z());
  }
  static Eigen::Array3i decode(std::uint64_t k) {
    const std::uint64_t mask = kSpan - 1;
    return {int(k >> 42), int((k >> 21) & mask), int(k & mask)};
  }
  // Fibonacci hashing: the top bits of the product depend on every bit of the key (the middle
  // bits ignored x, so a slab's cubes that differ only in x all probed one chain).
  std::size_t hash(std::uint64_t k) const {
    return std::size_t((k * 0x9E3779B97F4A7C15ull) >> hash_shift_);
  }

  double cell_;
  Eigen::Vector3d origin_;
  std::vector<std::uint32_t> order_;
  LargeVector<Eigen::Vector3d> sorted_;
  std::vector<std::uint32_t> starts_;
  std::vector<std::uint64_t> keys_;
  std::vector<std::int64_t> slots_;
  int hash_shift_ = 60;  // 64 − log2(slot count)
};

// The cube side: about the distance to the k-th neighbour, estimated from a kd-tree over every
// 16th point. How the k-th distance shrinks from that sample to the whole set depends on the
// set's dimension at that scale: with the square root of the density on a surface, with the cube
// root in a slab (a cloud whose noise is wider than its spacing). The dimension is read from the
// sample's k-th and 4k-th distances (4^(1/d) apart). The value only affects speed: every row is
// checked and the misses go to the kd-tree.
double gridCell(const Points& points, std::size_t k) {
  Points sample;
  for (std::size_t i = 0; i < points.size(); i += kEstimateStride) {
    sample.push_back(points[i]);
  }
  PointsAdaptor adaptor{&sample};
  const KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize));
  const std::size_t width = std::min(k, sample.size());
  const std::size_t wide = std::min(4 * k, sample.size());
  std::vector<double> distances(wide);
  std::vector<std::uint32_t> indices(wide);
  OrderedKnnResult found(wide, distances.data(), indices.data());
  std::vector<double> kth;
  std::vector<double> wide_kth;
  for (std::size_t i = 0; i < sample.size(); i += kEstimateStride) {
    found.reset();
    tree.findNeighbors(found, sample[i].data(), nanoflann::SearchParams());
    kth.push_back(std::sqrt(distances[width - 1]));
    wide_kth.push_back(std::sqrt(distances[wide - 1]));
  }
  const auto at = kth.size() * 3 / 4;
  std::nth_element(kth.begin(), kth.begin() + static_cast<std::ptrdiff_t>(at), kth.end());
  std::nth_element(
      wide_kth.begin(), wide_kth.begin() + static_cast<std::ptrdiff_t>(at), wide_kth.end());
  double dimension = 2.0;
  if (wide == 4 * k && wide_kth[at] > kth[at] && kth[at] > 0.0) {
    dimension = std::clamp(std::log(4.0) / std::log(wide_kth[at] / kth[at]), 2.0, 3.0);
  }
  return kCellOverKth * kth[at] * std::pow(double(kEstimateStride), -1.0 / dimension);
}

// Thread scratch of the grid search: the candidates around one cube, and one row.
struct GridScratch {
  std::vector<double> x, y, z;
  std::vector<std::uint32_t> index;
  std::vector<double> distance;
  std::vector<std::pair<double, std::uint32_t>> found;
};

// Rows of the points of cube c from the 3×3×3 cubes around it. A row is exact when its k-th
// distance is below the query's clearance to the outside of that block (any point outside is
// farther, by at least one coordinate); the others are appended to `misses`.
void gridRows(const PointGrid& grid,
              std::size_t c,
              GridScratch& scratch,
              NeighbourTable& table,
              std::vector<std::uint32_t>& misses) {
  const Eigen::Array3i cube = grid.cubeOf(c);
  scratch.x.clear();
  scratch.y.clear();
  scratch.z.clear();
  scratch.index.clear();
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dz = -1; dz <= 1; ++dz) {
        const std::int64_t other = grid.find(cube + Eigen::Array3i(dx, dy, dz));
        if (other < 0) {
          continue;
        }
        const auto o = static_cast<std::size_t>(other);
        for (std::size_t i = grid.start(o); i < grid.start(o + 1); ++i) {
          const Eigen::Vector3d& p = grid.position(i);
          scratch.x.push_back(p.x());
          scratch.y.push_back(p.y());
          scratch.z.push_back(p.z());
          scratch.index.push_back(grid.order()[i]);
        }
      }
    }
  }
  const auto width = static_cast<std::size_t>(table.k);
  const Eigen::Vector3d low = grid.corner(cube - 1);
  const Eigen::Vector3d high = grid.corner(cube + 2);
  // Margin for the rounding of the cube coordinates and of the distances.
  const double margin =
      1e-9 * (grid.cell() + low.cwiseAbs().maxCoeff() + high.cwiseAbs().maxCoeff());
  const std::size_t candidates = scratch.index.size();
  scratch.distance.resize(candidates);
  scratch.found.resize(candidates);
  double previous_kth = std::numeric_limits<double>::infinity();
  for (std::size_t i = grid.start(c); i < grid.start(c + 1); ++i) {
    const std::uint32_t point = grid.order()[i];
    const Eigen::Vector3d& q = grid.position(i);
    const double clearance = std::min((q - low).minCoeff(), (high - q).minCoeff()) - margin;
    if (candidates < width || !(clearance > 0.0)) {
      misses.push_back(point);
      continue;
    }
    for (std::size_t j = 0; j < candidates; ++j) {
      const double ex = q.x() - scratch.x[j];
      const double ey = q.y() - scratch.y[j];
      const double ez = q.z() - scratch.z[j];
      double distance = 0.0;  // summed as squaredDistance() does
      distance += ex * ex;
      distance += ey * ey;
      distance += ez * ez;
      scratch.distance[j] = distance;
    }
    // Only candidates inside the clearance can be in a provably exact row. Neighbouring queries
    // have similar k-th distances, so the previous row's (with a margin) usually bounds this one
    // more tightly and leaves few candidates to select from; when it leaves fewer than k, the
    // clearance is used. Either way the k nearest below a bound are exact when the bound is at
    // most the clearance: every point left out is at least that far.
    const double full_bound = clearance * clearance;
    std::size_t inside = 0;
    for (const double bound : {std::min(full_bound, kBoundGrowth * previous_kth), full_bound}) {
      inside = 0;  // branch-free compaction
      for (std::size_t j = 0; j < candidates; ++j) {
        scratch.found[inside] = {scratch.distance[j], scratch.index[j]};
        inside += scratch.distance[j] < bound ? 1 : 0;
      }
      if (inside >= width) {
        break;
      }
    }
    if (inside < width) {
      misses.push_back(point);
      continue;
    }
    // (distance, index) pairs order exactly as closerThan(): nearest first, ties by index.
    const auto end = scratch.found.begin() + static_cast<std::ptrdiff_t>(inside);
    const auto kth = scratch.found.begin() + static_cast<std::ptrdiff_t>(width - 1);
    std::nth_element(scratch.found.begin(), kth, end);
    previous_kth = kth->first;
    std::sort(scratch.found.begin(), kth);
    int* row = table.indices.data() + std::size_t(point) * width;
    for (std::size_t j = 0; j < width; ++j) {
      row[j] = static_cast<int>(scratch.found[j].second);
    }
  }
}

}  // namespace

double tableDistance(const Points& points, const NeighbourTable& table, int column) {
  std::vector<double> distances;
  for (std::size_t i = 0; column > 0 && column < table.k && i < points.size(); i += 7) {
    const auto other = static_cast<std::size_t>(table.of(i)[column]);
    distances.push_back(std::sqrt(squaredDistance(points[i], points[other])));
  }
  return median(std::move(distances));
}

// Large sets: a uniform grid with cubes about the k-th neighbour distance, all points of a cube
// answered from the 27 cubes around it (a few dozen candidates, contiguous in memory); rows that
// the block cannot prove exact, and small sets, go to the kd-tree. Either way a row is the exact
// k nearest with the kd-tree's distance and tie rule, so the table does not depend on the path a
// row took, nor on the thread count (each row is written once).
NeighbourTable nearestNeighbourTable(const Points& points, int k, const PointIndex* index) {
  NeighbourTable table;
  table.k = static_cast<int>(std::min(static_cast<std::size_t>(std::max(k, 0)), points.size()));
  if (table.k == 0) {
    return table;
  }
  const auto width = static_cast<std::size_t>(table.k);
  table.indices.resize(points.size() * width);
  std::vector<std::uint32_t> misses;
  const double cell = points.size() >= kGridMinimumPoints ? gridCell(points, width) : 0.0;
  if (!(cell > 0.0) || !std::isfinite(cell)) {
    misses.resize(points.size());
    std::iota(misses.begin(), misses.end(), 0u);
    kdTreeRows(points, misses, index, table);
    return table;
  }
  const PointGrid grid(points, cell);
  const auto cubes = static_cast<std::ptrdiff_t>(grid.cubes());
  std::vector<std::vector<std::uint32_t>> cube_misses(grid.cubes());
#pragma omp parallel
  {
    GridScratch scratch;
#pragma omp for schedule(dynamic, 64)
    for (std::ptrdiff_t c = 0; c < cubes; ++c) {
      gridRows(grid,
               static_cast<std::size_t>(c),
               scratch,
               table,
               cube_misses[static_cast<std::size_t>(c)]);
    }
  }
  for (const auto& list : cube_misses) {
    misses.insert(misses.end(), list.begin(), list.end());
  }
  if (misses.empty()) {
    return table;
  }
  if (misses.size() * points.size() <= kBruteForceWork) {
    bruteForceRows(points, misses, table);
  } else {
    kdTreeRows(points, misses, index, table);
  }
  return table;
}

}  // namespace internal

double medianSpacing(const Points& points, const PointIndex& index, std::size_t samples) {
  samples = std::min(points.size(), samples);
  std::vector<double> spacing;
  for (std::size_t s = 0; s < samples; ++s) {
    const auto neighbours = index.nearest(points[s * points.size() / samples], 2);
    if (neighbours.size() == 2) {
      spacing.push_back(std::sqrt(neighbours[1].squared_distance));
    }
  }
  if (spacing.empty()) {
    return 0.0;
  }
  auto middle = spacing.begin() + static_cast<long>(spacing.size() / 2);
  std::nth_element(spacing.begin(), middle, spacing.end());
  return *middle;
}

}  // namespace freeform_inspection
