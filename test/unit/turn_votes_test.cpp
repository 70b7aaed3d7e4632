// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// Translations of turned starts voted by the feature candidates (turn_votes_internal.h), on
// cells whose true correspondences and pose are known.
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "../../src/core/turn_votes_internal.h"
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace freeform_inspection
