// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/point_index.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace freeform_inspection {
namespace {

constexpr unsigned kSeed = 20260101;

Points randomPoints(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  Points points;
  for (int i = 0; i < count; ++i) {
    const double x = coordinate(rng);
    const double y = coordinate(rng);
    points.emplace_back(x, y, coordinate(rng));
  }
  return points;
}

// Summed in the order the index documents (x, y, z), so the distances must agree bit for bit.
double squaredDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    sum += (a[i] - b[i]) * (a[i] - b[i]);
  }
  return sum;
}

// Every point, nearest first, ties by index.
std::vector<Neighbour> bruteForce(const Points& points, const Eigen::Vector3d& query) {
  std::vector<Neighbour> all;
  for (std::size_t i = 0; i < points.size(); ++i) {
    all.push_back({static_cast<int>(i), squaredDistance(query, points[i])});
  }
  std::sort(all.begin(), all.end(), [](const Neighbour& a, const Neighbour& b) {
    return a.squared_distance < b.squared_distance ||
           (a.squared_distance == b.squared_distance && a.index < b.index);
  });
  return all;
}

std::vector<Neighbour> bruteNearest(const Points& points, const Eigen::Vector3d& query, int k) {
  std::vector<Neighbour> all = bruteForce(points, query);
  all.resize(std::min(all.size(), static_cast<std::size_t>(k)));
  return all;
}

std::vector<Neighbour> bruteWithin(const Points& points, const Eigen::Vector3d& query, double r) {
  std::vector<Neighbour> all = bruteForce(points, query);
  all.erase(
      std::remove_if(
          all.begin(), all.end(), [&](const Neighbour& n) { return n.squared_distance > r * r; }),
      all.end());
  return all;
}

void expectSame(const std::vector<Neighbour>& expected,
                const std::vector<Neighbour>& actual,
                const std::string& context) {
  ASSERT_EQ(expected.size(), actual.size()) << context;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(expected[i].index, actual[i].index) << context << " rank " << i;
    EXPECT_EQ(expected[i].squared_distance, actual[i].squared_distance) << context << " rank " << i;
  }
}

// Queries on indexed points (the point itself comes first) and at random places.
Points queries(const Points& points, unsigned seed) {
  Points result = randomPoints(50, seed + 1);
  for (std::size_t i = 0; i < points.size(); i += 97) {
    result.push_back(points[i]);
  }
  return result;
}

TEST(PointIndex, NearestMatchesBruteForceOnRandomPoints) {
  const Points points = randomPoints(2000, kSeed);
  const PointIndex index(points);
  ASSERT_EQ(index.size(), 2000u);
  for (const int k : {1, 7, 24, 100}) {
    for (const auto& query : queries(points, kSeed)) {
      expectSame(bruteNearest(points, query, k),
                 index.nearest(query, k),
                 "seed " + std::to_string(kSeed) + " k " + std::to_string(k));
    }
  }
}

TEST(PointIndex, WithinMatchesBruteForceOnRandomPoints) {
  const Points points = randomPoints(2000, kSeed);
  const PointIndex index(points);
  for (const double radius : {0.01, 0.1, 0.3, 4.0}) {
    for (const auto& query : queries(points, kSeed)) {
      expectSame(bruteWithin(points, query, radius),
                 index.within(query, radius),
                 "seed " + std::to_string(kSeed) + " radius " + std::to_string(radius));
    }
  }
}

// countWithin counts what within() finds, boundary included: lattice points exactly at the
// radius (0.5 from a lattice point) and random ones, radius zero, nothing for a bad query.
TEST(PointIndex, CountWithinIsTheSizeOfWithin) {
  const Points points = randomPoints(2000, kSeed);
  const PointIndex index(points);
  for (const double radius : {0.0, 0.01, 0.1, 0.3, 4.0}) {
    for (const auto& query : queries(points, kSeed)) {
      EXPECT_EQ(index.countWithin(query, radius), bruteWithin(points, query, radius).size())
          << "radius " << radius;
    }
  }
  Points lattice;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      lattice.emplace_back(0.5 * i, 0.5 * j, 0.0);
    }
  }
  const PointIndex grid(lattice);
  EXPECT_EQ(grid.countWithin(lattice[14], 0.5), 5u);  // itself and its four lattice neighbours
  EXPECT_EQ(grid.countWithin(lattice[14], 0.5), grid.within(lattice[14], 0.5).size());
  EXPECT_EQ(grid.countWithin(lattice[0], -1.0), 0u);
  EXPECT_EQ(grid.countWithin(Eigen::Vector3d(std::nan(""), 0.0, 0.0), 1.0), 0u);
  EXPECT_EQ(PointIndex(Points()).countWithin(Eigen::Vector3d::Zero(), 1.0), 0u);
}

TEST(PointIndex, QueryPointItselfComesFirstWithZeroDistance) {
  const Points points = randomPoints(2000, kSeed);
  const PointIndex index(points);
  const std::vector<Neighbour> found = index.nearest(points[123], 5);
  ASSERT_EQ(found.size(), 5u);
  EXPECT_EQ(found[0].index, 123);
  EXPECT_EQ(found[0].squared_distance, 0.0);
}

// A lattice is all ties: the lower index must win, at every rank and at the k-th boundary.
TEST(PointIndex, TiesOnALatticeAreBrokenByIndex) {
  Points lattice;
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      for (int l = 0; l < 8; ++l) {
        lattice.emplace_back(0.5 * i, 0.5 * j, 0.5 * l);
      }
    }
  }
  const PointIndex index(lattice);
  for (const auto& query : {lattice[0], lattice[273], Eigen::Vector3d(1.25, 1.25, 1.25)}) {
    for (const int k : {2, 5, 7, 19, 27}) {
      expectSame(bruteNearest(lattice, query, k), index.nearest(query, k), "lattice k");
    }
    expectSame(bruteWithin(lattice, query, 0.5), index.within(query, 0.5), "lattice r");
  }
}

// Wide balls are ordered by buckets of squared distance, not by a full sort: the order must
// still be the full sort's, rank for rank, where the points spread evenly over the squared
// radius (a plane through the query), where they all share one distance (a sphere about the
// query: one bucket), and where ties cross buckets (a lattice).
TEST(PointIndex, WithinOrdersWideBallsAsAFullSortDoes) {
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Points plane;
  Points sphere;
  for (int i = 0; i < 3000; ++i) {
    plane.emplace_back(unit(rng), unit(rng), 1e-3 * unit(rng));
    const Eigen::Vector3d direction(unit(rng), unit(rng), unit(rng));
    sphere.push_back(0.7 * direction.normalized());
  }
  Points lattice;
  for (int i = 0; i < 12; ++i) {
    for (int j = 0; j < 12; ++j) {
      for (int l = 0; l < 12; ++l) {
        lattice.emplace_back(0.25 * i, 0.25 * j, 0.25 * l);
      }
    }
  }
  const std::vector<std::pair<const Points*, std::string>> sets = {
      {&plane, "plane"}, {&sphere, "sphere"}, {&lattice, "lattice"}};
  for (const auto& [points, name] : sets) {
    const PointIndex index(*points);
    for (const Eigen::Vector3d& query :
         {Eigen::Vector3d(0.0, 0.0, 0.0), (*points)[17], Eigen::Vector3d(1.5, 1.5, 1.5)}) {
      for (const double radius : {0.4, 0.7, 1.5}) {
        const std::vector<Neighbour> expected = bruteWithin(*points, query, radius);
        expectSame(expected, index.within(query, radius), name + " r " + std::to_string(radius));
      }
    }
  }
}

// Many points at one place and radii whose square is denormal or zero: the buckets' width in r²
// would overflow, and the full sort orders them instead.
TEST(PointIndex, WithinOrdersCoincidentPointsAtTinyRadii) {
  Points points(200, Eigen::Vector3d(0.25, -0.5, 1.0));
  points.emplace_back(0.25, -0.5, 1.0 + 1e-170);
  const PointIndex index(points);
  for (const double radius : {0.0, 1e-200, 1e-165, 1.0}) {
    expectSame(bruteWithin(points, points[3], radius),
               index.within(points[3], radius),
               "coincident r " + std::to_string(radius));
  }
}

// spreadWithin is within() taken every s-th point, s = max(1, n / count), from the nearest.
TEST(PointIndex, SpreadWithinTakesEveryStrideThPointOfWithin) {
  const Points points = randomPoints(5000, kSeed);
  const PointIndex index(points);
  for (const double radius : {0.05, 0.5, 4.0}) {
    for (const std::size_t count : {std::size_t{1},
                                    std::size_t{7},
                                    std::size_t{192},
                                    std::numeric_limits<std::size_t>::max()}) {
      for (const auto& query : queries(points, kSeed)) {
        const std::vector<Neighbour> all = index.within(query, radius);
        const std::size_t stride = std::max<std::size_t>(1, all.size() / count);
        std::vector<Neighbour> expected;
        for (std::size_t j = 0; j < all.size(); j += stride) {
          expected.push_back(all[j]);
        }
        const std::vector<Neighbour> spread = index.spreadWithin(query, radius, count);
        expectSame(expected, spread, "count " + std::to_string(count));
        if (all.size() >= count) {
          EXPECT_LE(spread.size(), 2 * count - 1);
        } else {
          EXPECT_EQ(spread.size(), all.size());
        }
      }
    }
  }
  EXPECT_TRUE(index.spreadWithin(points[0], -1.0, 192).empty());
}

TEST(PointIndex, KLargerThanTheSetReturnsEveryPointSorted) {
  const Points points = randomPoints(10, kSeed);
  const PointIndex index(points);
  const Eigen::Vector3d query(0.1, 0.2, 0.3);
  const std::vector<Neighbour> found = index.nearest(query, 50);
  EXPECT_EQ(found.size(), 10u);
  expectSame(bruteNearest(points, query, 50), found, "k > size");
}

TEST(PointIndex, EmptySetAndNonPositiveKFindNothing) {
  const PointIndex empty{Points()};
  EXPECT_EQ(empty.size(), 0u);
  EXPECT_TRUE(empty.nearest(Eigen::Vector3d::Zero(), 5).empty());
  EXPECT_TRUE(empty.within(Eigen::Vector3d::Zero(), 1.0).empty());
  const PointIndex index(randomPoints(10, kSeed));
  EXPECT_TRUE(index.nearest(Eigen::Vector3d::Zero(), 0).empty());
  EXPECT_TRUE(index.nearest(Eigen::Vector3d::Zero(), -3).empty());
}

// `within` is inclusive: radius 0 finds exactly the points at the query, nothing elsewhere.
TEST(PointIndex, RadiusZeroFindsOnlyCoincidentPoints) {
  Points points = randomPoints(100, kSeed);
  points.push_back(points[42]);  // a duplicate: both must be found, lower index first
  const PointIndex index(points);
  const std::vector<Neighbour> found = index.within(points[42], 0.0);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].index, 42);
  EXPECT_EQ(found[1].index, 100);
  EXPECT_TRUE(index.within(Eigen::Vector3d(5.0, 5.0, 5.0), 0.0).empty());
  EXPECT_TRUE(index.within(points[0], -1.0).empty());
  EXPECT_TRUE(index.within(points[0], std::nan("")).empty());
}

TEST(PointIndex, NonFinitePointsAndQueriesAreIgnored) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Points points = randomPoints(20, kSeed);
  points[3] = Eigen::Vector3d(nan, 0.0, 0.0);
  points[7] = Eigen::Vector3d(0.0, std::numeric_limits<double>::infinity(), 0.0);
  const PointIndex index(points);
  EXPECT_EQ(index.size(), 20u);
  const std::vector<Neighbour> found = index.nearest(Eigen::Vector3d::Zero(), 100);
  EXPECT_EQ(found.size(), 18u);
  for (const auto& n : found) {
    EXPECT_NE(n.index, 3);
    EXPECT_NE(n.index, 7);
  }
  EXPECT_TRUE(index.nearest(Eigen::Vector3d(nan, 0.0, 0.0), 3).empty());
  EXPECT_TRUE(index.within(Eigen::Vector3d(nan, 0.0, 0.0), 1.0).empty());
}

// The batch answers each query as nearest(query, 1) would, whatever order it searches them in:
// random queries, indexed points (distance 0), a duplicate (lower index), non-finite queries.
TEST(PointIndex, NearestEachIsNearestOneForEveryQuery) {
  Points points = randomPoints(2000, kSeed);
  points.push_back(points[42]);
  const PointIndex index(points);
  Points batch = queries(points, kSeed);
  batch.push_back(points[42]);
  batch.emplace_back(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);
  const std::vector<Neighbour> found = index.nearestEach(batch);
  ASSERT_EQ(found.size(), batch.size());
  for (std::size_t q = 0; q + 1 < batch.size(); ++q) {
    expectSame(bruteNearest(points, batch[q], 1), {found[q]}, "query " + std::to_string(q));
  }
  EXPECT_EQ(found[batch.size() - 2].index, 42);
  EXPECT_EQ(found.back().index, -1);
  EXPECT_TRUE(PointIndex(Points()).nearestEach(batch).front().index == -1);
}

TEST(PointIndex, ConcurrentQueriesAgreeWithSerialOnes) {
  const Points points = randomPoints(2000, kSeed);
  const PointIndex index(points);
  const auto count = static_cast<std::ptrdiff_t>(points.size());
  std::vector<std::vector<Neighbour>> parallel(points.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    parallel[static_cast<std::size_t>(i)] = index.nearest(points[static_cast<std::size_t>(i)], 12);
  }
  for (std::size_t i = 0; i < points.size(); i += 13) {
    expectSame(index.nearest(points[i], 12), parallel[i], "parallel " + std::to_string(i));
  }
}

}  // namespace
}  // namespace freeform_inspection
