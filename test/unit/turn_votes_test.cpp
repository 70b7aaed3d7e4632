// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// Translations of turned starts voted by the feature candidates and by the surface
// (turn_votes_internal.h), on cells whose true correspondences and pose are known.
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "../../src/core/turn_votes_internal.h"
#include <gtest/gtest.h>
#include <omp.h>

namespace freeform_inspection {
namespace {

constexpr double kCell = 0.005;  // [m]

// 400 CAD cells spread over a 0.3 m box; the scan's cells are the first `features` of them seen
// at the pose `truth` (T_cad_scan), each with its true CAD cell among `decoys` random ones.
struct Case {
  SurfaceGraph cad;
  SurfaceGraph scan;
  std::vector<CorrespondenceResult> candidates{1};
};

Case makeCase(const Eigen::Isometry3d& truth, int features, int decoys, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coordinate(-0.15, 0.15);
  std::uniform_int_distribution<int> cell(0, 399);
  Case c;
  for (int i = 0; i < 400; ++i) {
    c.cad.centroids.emplace_back(coordinate(random), coordinate(random), coordinate(random));
  }
  for (int f = 0; f < features; ++f) {
    c.scan.centroids.push_back(truth.inverse() * c.cad.centroids[static_cast<std::size_t>(f)]);
    FeatureCandidates candidates;
    candidates.feature = f;
    for (int d = 0; d < decoys; ++d) {
      candidates.cad.push_back(cell(random));
    }
    candidates.cad.insert(candidates.cad.begin() + decoys / 2, f);
    c.candidates.front().features.push_back(candidates);
  }
  return c;
}

Eigen::Isometry3d pose(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation;
  T.translation() = translation;
  return T;
}

TEST(TurnVotes, TheRightRotationGetsTheTranslationItsTrueCandidatesVoteFor) {
  // A start with the true rotation but a translation 10 cm off (a turn about the wrong centre)
  // comes back where the truth is, within the cells' own spread; a rotation 90° off gets no
  // start: its votes scatter over the box and no three features agree.
  const Eigen::Isometry3d truth =
      pose(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix(),
           {0.4, -0.2, 0.1});
  const Case c = makeCase(truth, 12, 31, 7);
  const Eigen::Isometry3d off = pose(truth.linear(), {0.3, -0.1, 0.1});
  const Eigen::Isometry3d wrong = pose(
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()) * truth.linear(), truth.translation());
  const std::vector<Eigen::Isometry3d> starts = internal::votedTurnStarts(
      {wrong, off}, c.candidates, c.scan, c.cad, Eigen::Vector3d::Zero(), kCell);
  ASSERT_EQ(starts.size(), 1u);
  const double rotation_error =
      Eigen::AngleAxisd(starts[0].linear().transpose() * truth.linear()).angle();
  const double translation_error = (starts[0].translation() - truth.translation()).norm();
  std::printf("start: %.2e rad, %.2e m from the truth\n", rotation_error, translation_error);
  EXPECT_LT(rotation_error, 1e-12);
  EXPECT_LT(translation_error, 1e-9);  // every true vote is exact here
}

TEST(TurnVotes, TwoAgreeingFeaturesAreNotEnough) {
  const Eigen::Isometry3d truth =
      pose(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix(), {0.1, 0.0, -0.3});
  const Case two = makeCase(truth, 2, 31, 3);
  EXPECT_TRUE(internal::votedTurnStarts(
                  {truth}, two.candidates, two.scan, two.cad, Eigen::Vector3d::Zero(), kCell)
                  .empty());
  const Case three = makeCase(truth, 3, 31, 3);
  EXPECT_EQ(internal::votedTurnStarts(
                {truth}, three.candidates, three.scan, three.cad, Eigen::Vector3d::Zero(), kCell)
                .size(),
            1u);
}

TEST(TurnVotes, StartsThatAreOnePoseAreKeptOnceBestSupportedFirst) {
  // Two turns with the true rotation give one start; a third rotation that four of the features
  // also vote for (their candidates include the cells its pose lays them on) is kept after it.
  const Eigen::Isometry3d truth =
      pose(Eigen::AngleAxisd(1.0, Eigen::Vector3d(0, 1, 1).normalized()).toRotationMatrix(),
           {0.0, 0.2, 0.0});
  Case c = makeCase(truth, 10, 15, 11);
  const Eigen::Isometry3d other =
      pose(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()) * truth.linear(), {0.05, 0.2, 0.0});
  for (int f = 0; f < 4; ++f) {  // cells at the other pose's image of features 0-3
    c.cad.centroids.push_back(other * c.scan.centroids[static_cast<std::size_t>(f)]);
    c.candidates.front().features[static_cast<std::size_t>(f)].cad.push_back(
        static_cast<int>(c.cad.centroids.size()) - 1);
  }
  const std::vector<Eigen::Isometry3d> starts = internal::votedTurnStarts(
      {other, truth, truth}, c.candidates, c.scan, c.cad, Eigen::Vector3d::Zero(), kCell);
  ASSERT_EQ(starts.size(), 2u);
  EXPECT_LT((starts[0].translation() - truth.translation()).norm(), 1e-9);
  EXPECT_LT((starts[1].translation() - other.translation()).norm(), 1e-9);
}

// Cells every `step` metres on the faces of the box [low, high], with outward normals: the
// two boxes of an L-shaped block give a CAD whose cells are known.
void addBoxCells(const Eigen::Vector3d& low,
                 const Eigen::Vector3d& high,
                 double step,
                 SurfaceGraph* graph) {
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    for (const double side : {-1.0, 1.0}) {
      for (double a = low[u] + 0.5 * step; a < high[u]; a += step) {
        for (double b = low[v] + 0.5 * step; b < high[v]; b += step) {
          Eigen::Vector3d centroid;
          centroid[axis] = side < 0.0 ? low[axis] : high[axis];
          centroid[u] = a;
          centroid[v] = b;
          graph->centroids.push_back(centroid);
          graph->normals.push_back(side * Eigen::Vector3d::Unit(axis));
          graph->area.push_back(step * step);
        }
      }
    }
  }
}

// An L-block of 80 × 50 × 45 mm (a base plate and an upright, as test/data's machined block),
// its cells 2 mm apart; the scan sees the cells with x < 30 mm (the upright and the base's end)
// from the pose `truth`.
struct SurfaceCase {
  SurfaceGraph cad;
  SurfaceGraph scan;
};

SurfaceCase makeSurfaceCase(const Eigen::Isometry3d& truth) {
  constexpr double kStep = 0.002;
  SurfaceCase c;
  addBoxCells({0.0, 0.0, 0.0}, {0.08, 0.05, 0.015}, kStep, &c.cad);
  addBoxCells({0.0, 0.0, 0.015}, {0.02, 0.05, 0.045}, kStep, &c.cad);
  for (std::size_t i = 0; i < c.cad.size(); ++i) {
    if (c.cad.centroids[i].x() < 0.03) {
      c.scan.centroids.push_back(truth.inverse() * c.cad.centroids[i]);
      c.scan.normals.push_back(truth.linear().transpose() * c.cad.normals[i]);
      c.scan.area.push_back(c.cad.area[i]);
    }
  }
  return c;
}

TEST(TurnVotes, TheSurfaceVotesForTheTranslationOfATurnWithoutAnyFeature) {
  // A start with the true rotation 50 mm off (a turn about the wrong centre) comes back within a
  // cell of the truth (cells of 2 mm, bins of 4 cells); a rotation 37° off gets no start: the
  // normals of most cells agree with none of the CAD's.
  const Eigen::Isometry3d truth =
      pose(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix(),
           {0.4, -0.2, 0.1});
  const SurfaceCase c = makeSurfaceCase(truth);
  const double cell = 0.002;
  const Eigen::Isometry3d off =
      pose(truth.linear(), truth.translation() + Eigen::Vector3d(0.03, -0.02, 0.035));
  const Eigen::Isometry3d turned =
      pose(Eigen::AngleAxisd(37.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()) * truth.linear(),
           truth.translation());
  for (const bool oriented : {true, false}) {
    const std::vector<Eigen::Isometry3d> starts = internal::surfaceVotedTurnStarts(
        {turned, off}, c.scan, c.cad, oriented, Eigen::Vector3d::Zero(), cell);
    ASSERT_EQ(starts.size(), 1u);
    const double translation_error = (starts[0].translation() - truth.translation()).norm();
    std::printf("oriented %d: start %.2f mm from the truth\n", oriented, 1e3 * translation_error);
    EXPECT_LT(Eigen::AngleAxisd(starts[0].linear().transpose() * truth.linear()).angle(), 1e-12);
    EXPECT_LT(translation_error, cell);
  }
}

TEST(TurnVotes, TheSurfaceVotesAreTheSameWhateverTheThreadCount) {
  const Eigen::Isometry3d truth =
      pose(Eigen::AngleAxisd(0.7, Eigen::Vector3d(0, 1, 1).normalized()).toRotationMatrix(),
           {0.0, 0.2, 0.0});
  const SurfaceCase c = makeSurfaceCase(truth);
  std::vector<Eigen::Isometry3d> turns;
  for (int k = 0; k < 12; ++k) {  // the truth's rotation among others, each 10 mm off
    const Eigen::Matrix3d rotation =
        Eigen::AngleAxisd(k * M_PI / 6.0, Eigen::Vector3d::UnitY()) * truth.linear();
    turns.push_back(pose(rotation, truth.translation() + Eigen::Vector3d(0.01, 0.0, 0.0)));
  }
  const auto run = [&](int threads) {
    omp_set_num_threads(threads);
    return internal::surfaceVotedTurnStarts(
        turns, c.scan, c.cad, true, Eigen::Vector3d::Zero(), 0.002);
  };
  const std::vector<Eigen::Isometry3d> one = run(1);
  const std::vector<Eigen::Isometry3d> two = run(2);
  omp_set_num_threads(omp_get_num_procs());
  ASSERT_FALSE(one.empty());
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_TRUE(one[i].matrix() == two[i].matrix()) << "start " << i;
  }
  EXPECT_LT((one.front().translation() - truth.translation()).norm(), 0.002);
}

}  // namespace
}  // namespace freeform_inspection
