// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/support_plane.h"

#include <cmath>
#include <cstdio>
#include <random>

#include "analytic_clouds.h"
#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/mesh.h"
#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/synthetic_scan.h"

namespace freeform_inspection {
namespace {

constexpr unsigned kSeed = 11;

// A scene: the part's points first, then the table's.
struct Scene {
  Points points;
  std::size_t part = 0;  // the first `part` points are the part's
  double diameter = 0.0;
  double thickness = 0.0;                             // the part's principalThickness()
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // the table's, towards the part
};

// Gaussian noise of σ along `direction` on every point.
void addNoise(Points* points, const Eigen::Vector3d& direction, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, sigma);
  for (Eigen::Vector3d& p : *points) {
    p += gauss(rng) * direction;
  }
}

// A sphere of radius R resting on a square table of side `table_side` (z = 0), both with noise σ
// along z, then turned and moved to an arbitrary pose.
Scene sphereOnTable(double table_side, double sigma, int part_points, int table_points) {
  constexpr double kRadius = 0.05;
  Scene scene;
  scene.points = analytic::sampleSphere(kRadius, part_points, kSeed).points;
  for (Eigen::Vector3d& p : scene.points) {
    p.z() += kRadius;  // resting on z = 0
  }
  scene.part = scene.points.size();
  for (const Eigen::Vector3d& p :
       analytic::samplePlane(table_side, table_points, kSeed + 1).points) {
    // The table under the sphere only, as a scanner from above sees it.
    if (p.head<2>().norm() > 0.8 * kRadius) {
      scene.points.push_back(p);
    }
  }
  addNoise(&scene.points, Eigen::Vector3d::UnitZ(), sigma, kSeed + 2);
  scene.diameter = std::sqrt(12.0) * kRadius;  // the sphere's bounding-box diagonal
  scene.thickness = 2.0 * kRadius;
  const Eigen::Isometry3d pose =
      Eigen::Translation3d(0.3, -0.2, 0.9) *
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, -0.5).normalized());
  for (Eigen::Vector3d& p : scene.points) {
    p = pose * p;
  }
  scene.normal = pose.linear() * Eigen::Vector3d::UnitZ();
  return scene;
}

std::size_t removedOf(const SupportResult& result, std::size_t first, std::size_t last) {
  std::size_t removed = 0;
  for (std::size_t i = first; i < last; ++i) {
    removed += result.on_support[i] != 0 ? 1 : 0;
  }
  return removed;
}

TEST(SupportPlane, TableWiderThanThePartIsRemovedAndThePartKept) {
  constexpr double kSigma = 2e-4;
  const Scene scene = sphereOnTable(0.6, kSigma, 20000, 60000);
  const SupportResult result =
      findSupports(scene.points, kSigma, scene.diameter, scene.thickness, SupportConfig());
  ASSERT_EQ(result.planes.size(), 1u);
  const SupportPlane& table = result.planes.front();
  const std::size_t table_points = scene.points.size() - scene.part;
  const std::size_t part_lost = removedOf(result, 0, scene.part);
  const std::size_t table_removed = removedOf(result, scene.part, scene.points.size());
  std::printf(
      "table: %zu of %zu points removed, %zu of %zu part points, width %.3f m (L %.3f), "
      "normal error %.3f deg\n",
      table_removed,
      table_points,
      part_lost,
      scene.part,
      table.width,
      scene.diameter,
      std::acos(std::min(1.0, table.plane.head<3>().dot(scene.normal))) * 180.0 / M_PI);
  // Every table point within 4σ goes: all but the Gaussian tail beyond 4σ towards the part.
  EXPECT_GE(table_removed, table_points - table_points / 1000);
  // The part loses only its cap within 4σ of the table: a spherical cap of height h = 4σ (+ the
  // part's own noise) holds h / 2R of the sphere's points.
  EXPECT_LE(static_cast<double>(part_lost), 0.03 * static_cast<double>(scene.part));
  EXPECT_EQ(result.removed, table_removed + part_lost);
  EXPECT_GT(table.plane.head<3>().dot(scene.normal), std::cos(0.5 * M_PI / 180.0));
  EXPECT_GT(table.width, scene.diameter);
}

TEST(SupportPlane, FacesOfABoxAreNeverWiderThanThePart) {
  // A 100 × 20 × 10 mm bar: its largest face holds 2/3 of its points, and no face is wider than
  // the bar's diagonal.
  const Eigen::Vector3d half(0.05, 0.01, 0.005);
  Points points = test::sampleBoxSurface(half, 30000, kSeed);
  addNoise(&points, Eigen::Vector3d(0.3, 0.5, 0.8).normalized(), 5e-4, kSeed);
  const double diameter = 2.0 * half.norm();
  const SupportResult result =
      findSupports(points, 5e-4, diameter, 2.0 * half.z(), SupportConfig());
  EXPECT_TRUE(result.planes.empty());
  EXPECT_EQ(result.removed, 0u);
}

TEST(SupportPlane, ScatteredOutliersMakeNoSupport) {
  // A sphere with 20 % outliers spread through a box 2.5 × its size: no plane among them is wide
  // and dense enough to join into a patch wider than the part.
  Points points = analytic::sampleSphere(0.05, 20000, kSeed).points;
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> coordinate(-0.125, 0.125);
  for (int i = 0; i < 4000; ++i) {
    points.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng));
  }
  const SupportResult result =
      findSupports(points, 2e-4, std::sqrt(12.0) * 0.05, 0.1, SupportConfig());
  EXPECT_EQ(result.removed, 0u);
}

TEST(SupportPlane, OutliersPackedAroundAFlatPlateDoNotWidenItsFace) {
  // A 150 × 40 × 6 mm plate whose face is nearly as wide as its diagonal, with 40 % outliers in
  // its bounding box grown by 10 % per side (as the case generator makes them, at twice its
  // share) and noise of 0.5 % of L: the band about a face holds ~5 stray points in every cell
  // beyond the face, which must not join into a patch wider than the plate.
  const Eigen::Vector3d half(0.075, 0.02, 0.003);
  const double diameter = 2.0 * half.norm();
  const double sigma = 0.005 * diameter;
  Points points = test::sampleBoxSurface(half, 30000, kSeed);
  addNoise(&points, Eigen::Vector3d::UnitZ(), sigma, kSeed);
  std::mt19937 rng(kSeed + 5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 12000; ++i) {
    points.emplace_back(
        1.2 * half.x() * unit(rng), 1.2 * half.y() * unit(rng), 1.2 * half.z() * unit(rng));
  }
  const SupportResult result =
      findSupports(points, sigma, diameter, 2.0 * half.z(), SupportConfig());
  for (const SupportPlane& plane : result.planes) {
    std::printf("plate: a plane of %zu points, %.3f m wide (L %.3f m)\n",
                plane.points,
                plane.width,
                diameter);
  }
  EXPECT_EQ(result.removed, 0u);
}

TEST(SupportPlane, ANoiseBandThickerThanASlenderPartNeverSwallowsIt) {
  // Scans of a 100 × 20 × 10 mm bar from the case generator: σ = 0.5 % of L, 20 % outliers in
  // the bounding box grown by 10 % per side, arbitrary poses. The outliers inflate the measured
  // noise to ~1.3 % of L; at 4σ of 3× the true noise the band (±6 mm) held the whole bar and,
  // with the strays about it, measured wider than L: every seed's bar was removed as a table.
  // The band stays within a quarter of the bar's 10 mm.
  const Eigen::Vector3d half(0.05, 0.01, 0.005);
  const TriangleMesh bar = test::makeBox(half);
  const MeshQuery query(bar);
  const double diameter = 2.0 * half.norm();
  for (const std::uint64_t seed : {1, 2, 3}) {
    SyntheticScanConfig config;
    config.noise_ratio = 0.005;
    config.outlier_fraction = 0.2;
    config.seed = seed;
    const SyntheticScan scan = makeSyntheticScan(query, config);
    for (const double measured : {1.0, 3.0, 4.0}) {
      const SupportResult result = findSupports(scan.scan.points,
                                                measured * config.noise_ratio * diameter,
                                                diameter,
                                                principalThickness(bar),
                                                SupportConfig());
      EXPECT_EQ(result.removed, 0u) << "seed " << seed << ", measured noise " << measured << "σ";
    }
  }
}

TEST(SupportPlane, ThicknessIsTheExtentAlongTheAxisOfLeastSpread) {
  const Eigen::Isometry3d pose =
      Eigen::Translation3d(3.0, -1.0, 2.0) *
      Eigen::AngleAxisd(0.9, Eigen::Vector3d(1.0, 2.0, 3.0).normalized());
  TriangleMesh bar = test::makeBox(Eigen::Vector3d(0.05, 0.01, 0.005));
  for (Eigen::Vector3d& v : bar.vertices) {
    v = pose * v;
  }
  EXPECT_NEAR(principalThickness(bar), 0.01, 1e-9);
  EXPECT_EQ(principalThickness(TriangleMesh()), 0.0);
}

TEST(SupportPlane, NarrowStripOfTableIsKept) {
  // The table seen only as a 0.12 m square about the sphere (L = 0.173 m): no wider than the
  // part's diagonal, so nothing tells it from a face of the part (the registration then fails
  // safely).
  const Scene scene = sphereOnTable(0.12, 2e-4, 20000, 20000);
  const SupportResult result =
      findSupports(scene.points, 2e-4, scene.diameter, scene.thickness, SupportConfig());
  EXPECT_EQ(result.removed, 0u);
}

TEST(SupportPlane, SwitchedOffOrDegenerateInputsRemoveNothing) {
  const Scene scene = sphereOnTable(0.6, 2e-4, 5000, 15000);
  SupportConfig off;
  off.remove = false;
  EXPECT_EQ(findSupports(scene.points, 2e-4, scene.diameter, scene.thickness, off).removed, 0u);
  off.remove = true;
  off.max_planes = 0;
  EXPECT_EQ(findSupports(scene.points, 2e-4, scene.diameter, scene.thickness, off).removed, 0u);
  for (const Points& few : {Points(), Points{{0, 0, 0}, {1, 0, 0}}}) {
    const SupportResult result = findSupports(few, 0.0, 0.1, 0.05, SupportConfig());
    EXPECT_EQ(result.removed, 0u);
    EXPECT_EQ(result.on_support.size(), few.size());
  }
  // Every point on one plane (a flat scan): wider than a tiny part, removed whole; the cleaning
  // stage then refuses what is left, not this one.
  const Points flat = analytic::samplePlane(0.5, 2000, kSeed).points;
  EXPECT_EQ(findSupports(flat, 0.0, 0.1, 0.05, SupportConfig()).removed, flat.size());
}

TEST(SupportPlane, SameSceneGivesTheSameSupport) {
  const Scene scene = sphereOnTable(0.6, 2e-4, 10000, 30000);
  const SupportResult a =
      findSupports(scene.points, 2e-4, scene.diameter, scene.thickness, SupportConfig());
  const SupportResult b =
      findSupports(scene.points, 2e-4, scene.diameter, scene.thickness, SupportConfig());
  ASSERT_EQ(a.planes.size(), 1u);
  ASSERT_EQ(b.planes.size(), 1u);
  EXPECT_EQ(a.planes.front().plane, b.planes.front().plane);
  EXPECT_EQ(a.on_support, b.on_support);
}

TEST(SupportPlane, InvalidSettingsAreNamed) {
  SupportConfig config;
  config.max_planes = -1;
  config.min_share = 0.0;
  config.band_sigmas = std::nan("");
  const std::vector<std::string> errors = validate(config);
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_NE(errors[0].find("support.max_planes"), std::string::npos);
  EXPECT_NE(errors[1].find("support.min_share"), std::string::npos);
  EXPECT_NE(errors[2].find("support.band_sigmas"), std::string::npos);
  EXPECT_TRUE(validate(SupportConfig()).empty());
}

}  // namespace
}  // namespace freeform_inspection
