// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/synthetic_scan.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <vector>

#include "analytic_shapes.h"
#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;

Points toCad(const SyntheticScan& made) {
  Points points;
  for (const auto& p : made.scan.points) {
    points.push_back(made.T_cad_scan * p);
  }
  return points;
}

double diagonalOf(const MeshQuery& cad) {
  return computeBoundingBox(cad.mesh().vertices).diagonal();
}

TEST(SyntheticScan, NoiseFreeTruthMapsTheScanOntoTheCad) {
  const MeshQuery cad(test::makeBox(Eigen::Vector3d(0.1, 0.05, 0.02)));
  ASSERT_TRUE(cad.status().ok());
  const double diagonal = diagonalOf(cad);
  SyntheticScanConfig config;
  config.points = 5000;
  config.seed = 7;
  const SyntheticScan made = makeSyntheticScan(cad, config);
  ASSERT_TRUE(made.status.ok()) << made.status.message;
  ASSERT_EQ(made.scan.points.size(), 5000u);
  ASSERT_EQ(made.scan.normals.size(), 5000u);
  EXPECT_EQ(made.outliers, 0u);
  EXPECT_EQ(made.scan.width, 0);
  EXPECT_EQ(made.scan.height, 0);
  EXPECT_TRUE(made.scan.faces.empty());
  EXPECT_EQ(made.view_direction, Eigen::Vector3d::Zero());  // full scan: no view
  const Points in_cad = toCad(made);
  double sum = 0.0;
  double worst = 0.0;
  int normals_agree = 0;
  const std::vector<ClosestPoint> closest = cad.closest(in_cad);
  for (std::size_t i = 0; i < in_cad.size(); ++i) {
    ASSERT_TRUE(closest[i].found);
    sum += std::abs(closest[i].signed_distance);
    worst = std::max(worst, std::abs(closest[i].signed_distance));
    const Eigen::Vector3d n = made.T_cad_scan.linear() * made.scan.normals[i];
    EXPECT_NEAR(n.norm(), 1.0, 1e-12);
    // Only a point exactly on a box edge could be claimed by the other face.
    normals_agree += n.dot(closest[i].normal) > 1.0 - 1e-9 ? 1 : 0;
  }
  EXPECT_LT(sum / static_cast<double>(in_cad.size()), 1e-13 * diagonal);
  EXPECT_LT(worst, 1e-12 * diagonal);
  EXPECT_GE(normals_agree, 4995);
}

TEST(SyntheticScan, NoiseGivesTheHalfNormalMeanDistance) {
  const MeshQuery cad(test::makeBox(Eigen::Vector3d(0.1, 0.05, 0.02)));
  const double diagonal = diagonalOf(cad);
  SyntheticScanConfig config;
  config.points = 20000;
  config.noise_ratio = 0.001;
  config.seed = 11;
  const SyntheticScan made = makeSyntheticScan(cad, config);
  ASSERT_TRUE(made.status.ok()) << made.status.message;
  const double sigma = 0.001 * diagonal;
  double sum_abs = 0.0;
  double sum = 0.0;
  for (const auto& c : cad.closest(toCad(made))) {
    sum_abs += std::abs(c.signed_distance);
    sum += c.signed_distance;
  }
  const double n = 20000.0;
  // E|N(0, σ)| = σ·√(2/π); its standard error here is 0.6σ/√n ≈ 0.004σ: 3 % is ~6 of them
  // (points within σ of a box edge, ~0.1 % of them, are slightly closer to the other face).
  EXPECT_NEAR(sum_abs / n / (sigma * std::sqrt(2.0 / kPi)), 1.0, 0.03);
  EXPECT_NEAR(sum / n, 0.0, 5.0 * sigma / std::sqrt(n));
}

TEST(SyntheticScan, PosesAreUniformRotationsAndBoundedTranslations) {
  const MeshQuery cad(test::makeBox(Eigen::Vector3d(1.0, 1.0, 1.0)));
  const double diagonal = diagonalOf(cad);
  SyntheticScanConfig config;
  config.points = 1;
  config.min_translation_ratio = 0.5;
  config.max_translation_ratio = 1.5;
  constexpr int kSamples = 2000;
  double angle_sum = 0.0;
  int below_right_angle = 0;
  Eigen::Vector3d axis_sum = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction_sum = Eigen::Vector3d::Zero();
  double shortest = 1e9;
  double longest = 0.0;
  for (int seed = 1; seed <= kSamples; ++seed) {
    config.seed = static_cast<std::uint64_t>(seed);
    const SyntheticScan made = makeSyntheticScan(cad, config);
    ASSERT_TRUE(made.status.ok());
    const Eigen::Isometry3d T_scan_cad = made.T_cad_scan.inverse();
    const Eigen::AngleAxisd rotation(T_scan_cad.linear());
    angle_sum += rotation.angle();
    below_right_angle += rotation.angle() < kPi / 2.0 ? 1 : 0;
    axis_sum += rotation.axis();
    const double length = T_scan_cad.translation().norm() / diagonal;
    shortest = std::min(shortest, length);
    longest = std::max(longest, length);
    direction_sum += T_scan_cad.translation().normalized();
    // A rotation: orthonormal, determinant +1.
    EXPECT_NEAR(
        (T_scan_cad.linear() * T_scan_cad.linear().transpose() - Eigen::Matrix3d::Identity())
            .norm(),
        0.0,
        1e-12);
    EXPECT_NEAR(T_scan_cad.linear().determinant(), 1.0, 1e-12);
  }
  // Uniform on SO(3): the angle has density (1 − cos θ)/π on [0, π], mean π/2 + 2/π ≈ 2.207
  // and standard deviation ≈ 0.646, so the mean of 2000 has a standard error of 0.0144;
  // P(θ < π/2) = 1/2 − 1/π ≈ 0.182 (standard error 0.0086). Tolerances are ~4 of them.
  std::cout << "rotation angle mean " << angle_sum / kSamples << ", P(angle < pi/2) "
            << static_cast<double>(below_right_angle) / kSamples << " (seeds 1.." << kSamples
            << ")\n";
  EXPECT_NEAR(angle_sum / kSamples, kPi / 2.0 + 2.0 / kPi, 0.06);
  EXPECT_NEAR(static_cast<double>(below_right_angle) / kSamples, 0.5 - 1.0 / kPi, 0.035);
  // Axis and translation direction uniform on the sphere: components have σ = 1/√3.
  EXPECT_LT((axis_sum / kSamples).cwiseAbs().maxCoeff(), 0.06);
  EXPECT_LT((direction_sum / kSamples).cwiseAbs().maxCoeff(), 0.06);
  // |t| uniform in [0.5, 1.5] L: the extremes of 2000 draws come within 0.01 of the bounds.
  EXPECT_GE(shortest, 0.5);
  EXPECT_LE(longest, 1.5);
  EXPECT_LT(shortest, 0.51);
  EXPECT_GT(longest, 1.49);
}

TEST(SyntheticScan, PartialViewKeepsOnlyFacingUnoccludedPoints) {
  // A torus hides parts of itself from most directions.
  const MeshQuery cad(test::torus(0.1, 0.04, 48, 24));
  ASSERT_TRUE(cad.status().ok());
  const double diagonal = diagonalOf(cad);
  SyntheticScanConfig config;
  config.points = 4000;
  config.partial = true;
  config.seed = 5;
  const SyntheticScan made = makeSyntheticScan(cad, config);
  ASSERT_TRUE(made.status.ok()) << made.status.message;
  EXPECT_EQ(made.scan.points.size(), 4000u);
  const Eigen::Vector3d d = made.view_direction;
  EXPECT_NEAR(d.norm(), 1.0, 1e-12);
  const Points in_cad = toCad(made);
  for (std::size_t i = 0; i < in_cad.size(); ++i) {
    const Eigen::Vector3d n = made.T_cad_scan.linear() * made.scan.normals[i];
    EXPECT_GT(n.dot(d), 0.05 - 1e-12) << i;
    EXPECT_FALSE(cad.castRay(in_cad[i] + 1e-6 * diagonal * d, d, 0.0).hit) << i;
  }
  // The check above means something: of the facing points of a full scan, many are hidden.
  SyntheticScanConfig full = config;
  full.partial = false;
  const SyntheticScan all = makeSyntheticScan(cad, full);
  ASSERT_TRUE(all.status.ok());
  int facing = 0;
  int hidden = 0;
  const Points all_in_cad = toCad(all);
  for (std::size_t i = 0; i < all_in_cad.size(); ++i) {
    const Eigen::Vector3d n = all.T_cad_scan.linear() * all.scan.normals[i];
    if (n.dot(d) > 0.05) {
      ++facing;
      hidden += cad.castRay(all_in_cad[i] + 1e-6 * diagonal * d, d, 0.0).hit ? 1 : 0;
    }
  }
  std::cout << "torus seed 5: " << hidden << " of " << facing << " facing points hidden\n";
  EXPECT_GT(hidden, facing / 20);
}

TEST(SyntheticScan, PartialViewOfASphereIsAHemisphere) {
  const double radius = 0.05;
  const MeshQuery cad(test::icosphere(radius, 4));
  SyntheticScanConfig config;
  config.points = 5000;
  config.partial = true;
  config.seed = 3;
  const SyntheticScan made = makeSyntheticScan(cad, config);
  ASSERT_TRUE(made.status.ok()) << made.status.message;
  ASSERT_EQ(made.scan.points.size(), 5000u);
  const Eigen::Vector3d d = made.view_direction;
  double height_sum = 0.0;
  double lowest = 1.0;
  const Points in_cad = toCad(made);
  for (std::size_t i = 0; i < in_cad.size(); ++i) {
    const Eigen::Vector3d n = made.T_cad_scan.linear() * made.scan.normals[i];
    EXPECT_GT(n.dot(d), 0.05 - 1e-12);
    height_sum += in_cad[i].dot(d) / radius;
    lowest = std::min(lowest, in_cad[i].dot(d) / radius);
  }
  // Uniform by area on the cap cos θ ∈ [0.05, 1]: cos θ is uniform there, mean 0.525
  // (standard error 0.004); the lowest points sit on faces straddling the cut.
  EXPECT_NEAR(height_sum / 5000.0, 0.525, 0.02);
  EXPECT_GT(lowest, 0.0);
  EXPECT_LT(lowest, 0.1);
}

TEST(SyntheticScan, OutliersAreAppendedInsideTheGrownBox) {
  const MeshQuery cad(test::makeBox(Eigen::Vector3d(0.1, 0.05, 0.02)));
  const double diagonal = diagonalOf(cad);
  SyntheticScanConfig config;
  config.points = 2000;
  config.outlier_fraction = 0.1;
  config.seed = 13;
  const SyntheticScan made = makeSyntheticScan(cad, config);
  ASSERT_TRUE(made.status.ok()) << made.status.message;
  ASSERT_EQ(made.outliers, 200u);
  ASSERT_EQ(made.scan.points.size(), 2200u);
  ASSERT_EQ(made.scan.normals.size(), 2200u);
  const Points in_cad = toCad(made);
  const BoundingBox surface = computeBoundingBox(Points(in_cad.begin(), in_cad.begin() + 2000));
  const Eigen::Vector3d low = surface.min - 0.1 * surface.extent();
  const Eigen::Vector3d high = surface.max + 0.1 * surface.extent();
  const std::vector<ClosestPoint> closest = cad.closest(in_cad);
  int off_surface = 0;
  BoundingBox spread{in_cad[2000], in_cad[2000]};
  for (std::size_t i = 0; i < 2200; ++i) {
    EXPECT_NEAR(made.scan.normals[i].norm(), 1.0, 1e-12);
    if (i < 2000) {
      EXPECT_LT(std::abs(closest[i].signed_distance), 1e-12 * diagonal) << i;
      continue;
    }
    const Eigen::Vector3d& p = in_cad[i];
    EXPECT_TRUE((p.array() >= low.array() - 1e-12).all() &&
                (p.array() <= high.array() + 1e-12).all())
        << i;
    off_surface += std::abs(closest[i].signed_distance) > 1e-4 * diagonal ? 1 : 0;
    spread.min = spread.min.cwiseMin(p);
    spread.max = spread.max.cwiseMax(p);
  }
  EXPECT_GT(off_surface, 190);
  // 200 uniform draws fill most of the grown box along every axis.
  EXPECT_GT((spread.extent().array() / (high - low).array()).minCoeff(), 0.9);
}

TEST(SyntheticScan, SameSeedSameCaseOtherSeedOtherCase) {
  const MeshQuery cad(test::torus(0.1, 0.03, 32, 16));
  SyntheticScanConfig config;
  config.points = 3000;
  config.partial = true;
  config.noise_ratio = 0.002;
  config.outlier_fraction = 0.05;
  config.seed = 99;
  const SyntheticScan a = makeSyntheticScan(cad, config);
  const SyntheticScan b = makeSyntheticScan(cad, config);
  ASSERT_TRUE(a.status.ok()) << a.status.message;
  EXPECT_EQ(a.scan.points, b.scan.points);
  EXPECT_EQ(a.scan.normals, b.scan.normals);
  EXPECT_EQ(a.T_cad_scan.matrix(), b.T_cad_scan.matrix());
  EXPECT_EQ(a.view_direction, b.view_direction);
  EXPECT_EQ(a.outliers, b.outliers);
  config.seed = 100;
  const SyntheticScan c = makeSyntheticScan(cad, config);
  ASSERT_TRUE(c.status.ok());
  EXPECT_NE(a.scan.points, c.scan.points);
  EXPECT_FALSE(a.T_cad_scan.matrix().isApprox(c.T_cad_scan.matrix()));
  EXPECT_FALSE(a.view_direction.isApprox(c.view_direction));
  // The pose depends on the seed only, not on how many points are drawn.
  config.seed = 99;
  config.points = 10;
  EXPECT_EQ(makeSyntheticScan(cad, config).T_cad_scan.matrix(), a.T_cad_scan.matrix());
}

TEST(SyntheticScan, APlaneSeenFromBehindIsAFailure) {
  const MeshQuery cad(test::planarGrid(0.1, 4));  // faces +z only
  SyntheticScanConfig config;
  config.points = 100;
  config.partial = true;
  int seen = 0;
  int unseen = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    config.seed = seed;
    const SyntheticScan made = makeSyntheticScan(cad, config);
    if (made.view_direction.z() > 0.05) {
      ASSERT_TRUE(made.status.ok()) << seed;
      EXPECT_EQ(made.scan.points.size(), 100u);
      ++seen;
    } else {
      EXPECT_EQ(made.status.code, StatusCode::kDegenerateInput) << seed;
      EXPECT_TRUE(made.scan.points.empty());
      ++unseen;
    }
  }
  EXPECT_GT(seen, 0);
  EXPECT_GT(unseen, 0);
}

TEST(SyntheticScan, InvalidConfigsFail) {
  const MeshQuery cad(test::makeBox(Eigen::Vector3d(1.0, 1.0, 1.0)));
  const double nan = std::nan("");
  std::vector<SyntheticScanConfig> bad(9);
  bad[0].points = 0;
  bad[1].noise_ratio = -0.1;
  bad[2].noise_ratio = nan;
  bad[3].outlier_fraction = -0.01;
  bad[4].outlier_fraction = std::numeric_limits<double>::infinity();
  bad[5].min_translation_ratio = -1.0;
  bad[6].min_translation_ratio = 2.0;  // > max 1.5
  bad[7].max_translation_ratio = nan;
  bad[8].min_translation_ratio = nan;
  for (std::size_t i = 0; i < bad.size(); ++i) {
    const SyntheticScan made = makeSyntheticScan(cad, bad[i]);
    EXPECT_EQ(made.status.code, StatusCode::kInvalidInput) << i;
    EXPECT_FALSE(made.status.message.empty()) << i;
    EXPECT_TRUE(made.scan.points.empty()) << i;
  }
  const MeshQuery empty{TriangleMesh{}};
  const SyntheticScan made = makeSyntheticScan(empty, SyntheticScanConfig{});
  EXPECT_FALSE(made.status.ok());
  EXPECT_TRUE(made.scan.points.empty());
}

}  // namespace
}  // namespace freeform_inspection
