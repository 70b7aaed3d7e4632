// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/defects.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

#include "cloud_neighbours_internal.h"

#include "freeform_inspection/mesh.h"
#include "freeform_inspection/point_index.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Clouds: each out-of-tolerance point joins its nearest neighbours of the same sign. Ten keep a
// random sampling well connected (a random graph falls apart below ~4.5 neighbours per point).
constexpr int kJoinNeighbours = 10;
// The whole cloud's neighbour table replaces per-point queries from 1/8 of it out of tolerance.
constexpr std::size_t kTableShare = 8;

// -1 missing material, +1 excess, 0 within tolerance or unmatched.
int outsideSign(float deviation, const ToleranceConfig& tolerance) {
  if (!std::isfinite(deviation)) {
    return 0;
  }
  if (deviation > tolerance.upper) {
    return 1;
  }
  return deviation < tolerance.lower ? -1 : 0;
}

class DisjointSets {
 public:
  explicit DisjointSets(std::size_t size) : parent_(size) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void join(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) {
      parent_[std::max(a, b)] = std::min(a, b);  // smallest index is the root: deterministic
    }
  }

 private:
  std::vector<std::size_t> parent_;
};

// Surface area each point stands for. Meshes: a third of every triangle around it. Clouds:
// a disc of six spacings divided among the points in it (within 2 % on a grid and for
// uniform random sampling; overestimated up to twice at the border of the scan).
std::vector<double> pointAreas(const Points& points,
                               const Triangles& faces,
                               const std::vector<std::size_t>& wanted,
                               const PointIndex* index,
                               double spacing) {
  std::vector<double> area(points.size(), 0.0);
  if (!faces.empty()) {
    for (const auto& face : faces) {
      const double third = triangleArea(points, face) / 3.0;
      for (int c = 0; c < 3; ++c) {
        area[static_cast<std::size_t>(face[c])] += third;
      }
    }
    return area;
  }
  const double radius = 6.0 * spacing;
  const auto count = static_cast<long>(wanted.size());
#pragma omp parallel for schedule(static)
  for (long k = 0; k < count; ++k) {
    const std::size_t i = wanted[static_cast<std::size_t>(k)];
    const auto inside = static_cast<double>(index->countWithin(points[i], radius));
    area[i] = kPi * radius * radius / std::max(1.0, inside - 0.5);
  }
  return area;
}

}  // namespace

struct DefectNeighbourhood::Impl {
  const Points& points;
  const Triangles& faces;
  std::unique_ptr<PointIndex> index;                // clouds, on first need
  double spacing = 0.0;                             // median spacing, with the index
  bool finite = false;                              // every point finite, with the index
  std::unique_ptr<internal::NeighbourTable> table;  // clouds, when much is out of tolerance

  const PointIndex& cloudIndex() {
    if (!index) {
      index = std::make_unique<PointIndex>(points);
      spacing = medianSpacing(points, *index);
      finite = std::all_of(
          points.begin(), points.end(), [](const Eigen::Vector3d& p) { return p.allFinite(); });
    }
    return *index;
  }

  const internal::NeighbourTable& neighbourTable() {
    if (!table) {
      table = std::make_unique<internal::NeighbourTable>(
          internal::nearestNeighbourTable(points, kJoinNeighbours + 1, &cloudIndex()));
    }
    return *table;
  }
};

DefectNeighbourhood::DefectNeighbourhood(const Points& points_cad, const Triangles& faces)
    : impl_(new Impl{points_cad, faces, nullptr, 0.0, false, nullptr}) {}

DefectNeighbourhood::~DefectNeighbourhood() = default;

std::vector<std::string> validate(const DefectConfig& config) {
  std::vector<std::string> errors;
  if (config.min_points < 1) {
    errors.push_back("defects.min_points must be at least 1");
  }
  if (!(std::isfinite(config.min_area) && config.min_area >= 0.0)) {
    errors.push_back("defects.min_area must be a finite area >= 0");
  }
  if (!(config.neighbour_spacings >= 1.0 && config.neighbour_spacings <= 100.0)) {
    errors.push_back("defects.neighbour_spacings must be in [1, 100]");
  }
  return errors;
}

DefectResult findDefects(const Points& points_cad,
                         const Triangles& faces,
                         const std::vector<float>& deviation,
                         const ToleranceBands& tolerance,
                         const DefectConfig& config) {
  DefectNeighbourhood neighbourhood(points_cad, faces);
  return findDefects(neighbourhood, deviation, tolerance, config);
}

DefectResult findDefects(DefectNeighbourhood& neighbourhood,
                         const std::vector<float>& deviation,
                         const ToleranceBands& tolerance,
                         const DefectConfig& config) {
  DefectNeighbourhood::Impl& surface = *neighbourhood.impl_;
  const Points& points_cad = surface.points;
  const Triangles& faces = surface.faces;
  DefectResult result;
  result.point_region.assign(points_cad.size(), -1);
  // Each out-of-band point's side and region in one number, (region + 2) × sign, so that the
  // joins below, which compare it, keep one sign and one region per defect.
  std::vector<int> sign(points_cad.size(), 0);
  std::vector<std::size_t> outside;
  for (std::size_t i = 0; i < points_cad.size(); ++i) {
    sign[i] = outsideSign(deviation[i], tolerance.at(i)) * (tolerance.regionAt(i) + 2);
    if (sign[i] != 0) {
      outside.push_back(i);
    }
  }
  if (outside.size() < static_cast<std::size_t>(config.min_points)) {
    return result;
  }
  // Out-of-tolerance points of one sign that are neighbours on the scan surface join.
  DisjointSets sets(points_cad.size());
  const PointIndex* index = nullptr;
  double spacing = 0.0;
  if (!faces.empty()) {
    for (const auto& face : faces) {
      for (int c = 0; c < 3; ++c) {
        const auto a = static_cast<std::size_t>(face[c]);
        const auto b = static_cast<std::size_t>(face[(c + 1) % 3]);
        if (sign[a] != 0 && sign[a] == sign[b]) {
          sets.join(a, b);
        }
      }
    }
  } else {
    index = &surface.cloudIndex();
    spacing = surface.spacing;
    const double reach = config.neighbour_spacings * spacing;
    const auto sameSide = [&](std::size_t i, int j, double squared_distance) {
      return squared_distance <= reach * reach && sign[static_cast<std::size_t>(j)] == sign[i];
    };
    // The nearest few within reach: a bounded cost however dense or noisy the cloud is. When
    // much of the scan is out of tolerance (a band far below the noise), one neighbour table of
    // the whole cloud on a grid costs a tenth of a kd-tree query per point; its rows are the
    // kd-tree's answers, so the regions are the same either way.
    if (surface.finite && outside.size() * kTableShare >= points_cad.size()) {
      const internal::NeighbourTable& table = surface.neighbourTable();
      for (const std::size_t i : outside) {
        for (const int* j = table.of(i); j != table.of(i) + table.k; ++j) {
          const auto other = static_cast<std::size_t>(*j);
          if (sameSide(i, *j, internal::squaredDistance(points_cad[i], points_cad[other]))) {
            sets.join(i, other);
          }
        }
      }
    } else {
      // Queries in parallel, joined in order afterwards (the sets are not thread-safe).
      std::vector<std::vector<int>> same_side(outside.size());
      const auto count = static_cast<long>(outside.size());
#pragma omp parallel for schedule(dynamic, 256)
      for (long k = 0; k < count; ++k) {
        const std::size_t i = outside[static_cast<std::size_t>(k)];
        for (const Neighbour& n : index->nearest(points_cad[i], kJoinNeighbours + 1)) {
          if (sameSide(i, n.index, n.squared_distance)) {
            same_side[static_cast<std::size_t>(k)].push_back(n.index);
          }
        }
      }
      for (std::size_t k = 0; k < outside.size(); ++k) {
        for (const int j : same_side[k]) {
          sets.join(outside[k], static_cast<std::size_t>(j));
        }
      }
    }
  }
  // Each point's region root, found once: the loops below visit every member several times.
  std::vector<std::size_t> root(points_cad.size(), 0);
  std::vector<std::size_t> members(points_cad.size(), 0);
  for (const std::size_t i : outside) {
    root[i] = sets.find(i);
    ++members[root[i]];
  }
  std::vector<std::size_t> kept;
  for (const std::size_t i : outside) {
    if (members[root[i]] >= static_cast<std::size_t>(config.min_points)) {
      kept.push_back(i);
    }
  }
  std::vector<int> region_of_root(points_cad.size(), -1);
  std::vector<DefectRegion> regions;
  for (const std::size_t i : kept) {
    if (region_of_root[root[i]] < 0) {
      region_of_root[root[i]] = static_cast<int>(regions.size());
      DefectRegion region;
      region.sign = sign[i] > 0 ? 1 : -1;
      region.region = tolerance.regionAt(i);
      region.bbox_min = region.bbox_max = points_cad[i];
      regions.push_back(region);
    }
    DefectRegion& region = regions[static_cast<std::size_t>(region_of_root[root[i]])];
    const double d = deviation[i];
    ++region.points;
    region.centroid += points_cad[i];
    region.mean += d;
    region.bbox_min = region.bbox_min.cwiseMin(points_cad[i]);
    region.bbox_max = region.bbox_max.cwiseMax(points_cad[i]);
    if (std::abs(d) > std::abs(region.peak)) {
      region.peak = d;
    }
  }
  // Area: exact per point on a mesh; on a cloud, the mean area per point of at most 64 evenly
  // spread members times the member count (a density query per member would cost more than
  // everything else when a band far below the noise puts the whole scan out of tolerance).
  constexpr std::size_t kAreaSamples = 64;
  std::vector<std::size_t> seen(regions.size(), 0);
  std::vector<std::size_t> sampled;
  for (const std::size_t i : kept) {
    const auto r = static_cast<std::size_t>(region_of_root[root[i]]);
    const std::size_t stride =
        faces.empty() ? (regions[r].points + kAreaSamples - 1) / kAreaSamples : 1;
    if (seen[r]++ % stride == 0) {
      sampled.push_back(i);
    }
  }
  const std::vector<double> area = pointAreas(points_cad, faces, sampled, index, spacing);
  std::vector<double> area_sum(regions.size(), 0.0);
  std::vector<std::size_t> area_count(regions.size(), 0);
  for (const std::size_t i : sampled) {
    const auto r = static_cast<std::size_t>(region_of_root[root[i]]);
    area_sum[r] += area[i];
    ++area_count[r];
  }
  for (std::size_t r = 0; r < regions.size(); ++r) {
    regions[r].area = area_count[r] == 0 ? 0.0
                                         : area_sum[r] / static_cast<double>(area_count[r]) *
                                               static_cast<double>(regions[r].points);
  }
  for (DefectRegion& region : regions) {
    region.centroid /= static_cast<double>(region.points);
    region.mean /= static_cast<double>(region.points);
  }
  // Regions under min_area are dropped (an area the estimate could not give is kept); the rest,
  // largest |peak| first; ties by size, then by the order found (stable).
  std::vector<int> order;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    if (!(regions[r].area < config.min_area)) {
      order.push_back(static_cast<int>(r));
    }
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const auto& ra = regions[static_cast<std::size_t>(a)];
    const auto& rb = regions[static_cast<std::size_t>(b)];
    if (std::abs(ra.peak) != std::abs(rb.peak)) {
      return std::abs(ra.peak) > std::abs(rb.peak);
    }
    return ra.points > rb.points;
  });
  std::vector<int> rank(regions.size(), -1);
  for (std::size_t r = 0; r < order.size(); ++r) {
    rank[static_cast<std::size_t>(order[r])] = static_cast<int>(r);
    result.regions.push_back(regions[static_cast<std::size_t>(order[r])]);
  }
  for (const std::size_t i : kept) {
    result.point_region[i] = rank[static_cast<std::size_t>(region_of_root[root[i]])];
  }
  return result;
}

}  // namespace freeform_inspection
