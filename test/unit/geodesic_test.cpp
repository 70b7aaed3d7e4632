// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/geodesic.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <random>
#include <tuple>
#include <utility>

#include <gtest/gtest.h>

namespace freeform_inspection {
namespace {

constexpr unsigned kSeed = 20261201;

// A graph from undirected (a, b, length) links, as CSR with each link both ways.
SurfaceGraph graphOf(std::size_t cells, const std::vector<std::tuple<int, int, double>>& links) {
  SurfaceGraph graph;
  graph.centroids.assign(cells, Eigen::Vector3d::Zero());
  std::vector<std::vector<std::pair<int, double>>> out(cells);
  for (const auto& [a, b, length] : links) {
    out[static_cast<std::size_t>(a)].emplace_back(b, length);
    out[static_cast<std::size_t>(b)].emplace_back(a, length);
  }
  graph.offsets.push_back(0);
  for (const auto& row : out) {
    for (const auto& [to, length] : row) {
      graph.neighbours.push_back(to);
      graph.lengths.push_back(length);
    }
    graph.offsets.push_back(graph.neighbours.size());
  }
  return graph;
}

// A w × h grid of cells jittered off their lattice points, linked to their 8 neighbours by the
// distance between them: links from ~0.3 to ~2 lattice steps, like the cells of a scan.
SurfaceGraph jitteredGrid(int w, int h, double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  std::vector<Eigen::Vector2d> at;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      at.emplace_back(x + offset(rng), y + offset(rng));
    }
  }
  std::vector<std::tuple<int, int, double>> links;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (const auto& [dx, dy] : {std::pair{1, 0}, {0, 1}, {1, 1}, {1, -1}}) {
        const int nx = x + dx;
        const int ny = y + dy;
        if (nx < w && ny >= 0 && ny < h) {
          const int a = y * w + x;
          const int b = ny * w + nx;
          links.emplace_back(a, b, (at[std::size_t(a)] - at[std::size_t(b)]).norm());
        }
      }
    }
  }
  return graphOf(at.size(), links);
}

// Textbook Dijkstra (a binary heap of (distance, cell), stale entries skipped), the reference
// the grower's pop order must match exactly.
std::vector<BallMember> referenceBall(const SurfaceGraph& graph, int source, double radius) {
  std::vector<double> distance(graph.size(), std::numeric_limits<double>::infinity());
  std::priority_queue<std::pair<double, int>,
                      std::vector<std::pair<double, int>>,
                      std::greater<std::pair<double, int>>>
      queue;
  std::vector<BallMember> ball;
  distance[static_cast<std::size_t>(source)] = 0.0;
  queue.emplace(0.0, source);
  while (!queue.empty()) {
    const auto [d, cell] = queue.top();
    queue.pop();
    const auto c = static_cast<std::size_t>(cell);
    if (d > distance[c]) {
      continue;
    }
    ball.push_back({cell, d});
    for (std::size_t e = graph.offsets[c]; e < graph.offsets[c + 1]; ++e) {
      const double through = d + graph.lengths[e];
      const auto next = static_cast<std::size_t>(graph.neighbours[e]);
      if (through <= radius && through < distance[next]) {
        distance[next] = through;
        queue.emplace(through, graph.neighbours[e]);
      }
    }
  }
  return ball;
}

// Every ball of the graph equals the reference, member by member, distances bit for bit; returns
// the members compared.
std::size_t expectReferenceBalls(const SurfaceGraph& graph, double radius) {
  GeodesicBallGrower grower(graph);
  std::size_t members = 0;
  for (std::size_t c = 0; c < graph.size(); ++c) {
    const auto expected = referenceBall(graph, static_cast<int>(c), radius);
    const auto& ball = grower.grow(static_cast<int>(c), radius);
    EXPECT_EQ(ball.size(), expected.size()) << "source " << c;
    for (std::size_t i = 0; i < std::min(ball.size(), expected.size()); ++i) {
      EXPECT_EQ(ball[i].cell, expected[i].cell) << "source " << c << " member " << i;
      EXPECT_EQ(ball[i].distance, expected[i].distance) << "source " << c << " member " << i;
    }
    members += ball.size();
  }
  return members;
}

TEST(Geodesic, PathGraphDistancesAreSumsOfLinks) {
  const SurfaceGraph graph = graphOf(4, {{0, 1, 1.0}, {1, 2, 2.0}, {2, 3, 0.5}});
  GeodesicBallGrower grower(graph);
  const auto& ball = grower.grow(0, 3.0);
  ASSERT_EQ(ball.size(), 3u);  // cell 3 is 3.5 away
  EXPECT_EQ(ball[0].cell, 0);
  EXPECT_EQ(ball[1].cell, 1);
  EXPECT_EQ(ball[2].cell, 2);
  EXPECT_DOUBLE_EQ(ball[2].distance, 3.0);  // the radius is inclusive
}

TEST(Geodesic, ShorterDetourWinsOverDirectLink) {
  // 0–2 directly 3.0, or through 1 in 1.0 + 1.5.
  const SurfaceGraph graph = graphOf(3, {{0, 2, 3.0}, {0, 1, 1.0}, {1, 2, 1.5}});
  GeodesicBallGrower grower(graph);
  const auto& ball = grower.grow(0, 10.0);
  ASSERT_EQ(ball.size(), 3u);
  EXPECT_EQ(ball[2].cell, 2);
  EXPECT_DOUBLE_EQ(ball[2].distance, 2.5);
}

// The bucketed queue (buckets one shortest link wide) pops exactly as a binary heap does, on a
// scan-like graph and over several radii; seed printed for reproduction.
TEST(Geodesic, BucketedBallsEqualBinaryHeapDijkstra) {
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  const SurfaceGraph graph = jitteredGrid(30, 25, 0.35, kSeed);
  const double shortest = *std::min_element(graph.lengths.begin(), graph.lengths.end());
  ASSERT_GT(shortest, 0.1);  // the bucketed path is the one taken: radius / link < 4096
  for (const double radius : {0.5, 2.0, 6.0, 11.0}) {
    EXPECT_GT(expectReferenceBalls(graph, radius), graph.size()) << "radius " << radius;
  }
}

// Equal distances by different paths (an exact lattice) keep the reference's tie order: by cell.
TEST(Geodesic, TiesAreOrderedByCellAsAHeapWould) {
  const SurfaceGraph graph = jitteredGrid(12, 12, 0.0, kSeed);
  EXPECT_GT(expectReferenceBalls(graph, 4.0), graph.size());
}

// A near-zero link (two cells with almost the same centroid) would need millions of buckets;
// the grower falls back to one heap and still matches.
TEST(Geodesic, NearZeroLinkFallsBackToOneHeap) {
  SurfaceGraph graph = jitteredGrid(10, 10, 0.3, kSeed + 1);
  graph.lengths[0] = 1e-9;  // the first link both ways
  for (std::size_t e = graph.offsets[1]; e < graph.offsets[2]; ++e) {
    if (graph.neighbours[e] == 0) {
      graph.lengths[e] = 1e-9;
    }
  }
  EXPECT_GT(expectReferenceBalls(graph, 5.0), graph.size());
  SurfaceGraph zero = jitteredGrid(6, 6, 0.3, kSeed + 2);
  std::fill(zero.lengths.begin(), zero.lengths.begin() + 1, 0.0);
  for (std::size_t e = zero.offsets[1]; e < zero.offsets[2]; ++e) {
    if (zero.neighbours[e] == 0) {
      zero.lengths[e] = 0.0;
    }
  }
  EXPECT_GT(expectReferenceBalls(zero, 3.0), zero.size());
}

// One grower serves balls of different radii in a row (the pipeline's) without leftovers.
TEST(Geodesic, ReusedGrowerForgetsThePreviousBall) {
  const SurfaceGraph graph = jitteredGrid(15, 15, 0.3, kSeed + 3);
  GeodesicBallGrower grower(graph);
  const std::size_t wide = grower.grow(112, 6.0).size();
  const std::size_t narrow = grower.grow(0, 1.0).size();
  EXPECT_EQ(narrow, referenceBall(graph, 0, 1.0).size());
  EXPECT_EQ(grower.grow(112, 6.0).size(), wide);
}

}  // namespace
}  // namespace freeform_inspection
