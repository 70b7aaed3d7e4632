// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "analytic_clouds.h"
#include <gtest/gtest.h>

#include "freeform_inspection/curvature.h"
#include "freeform_inspection/point_index.h"
#include "freeform_inspection/surface_graph.h"

// The shared k-nearest-neighbour table is internal to the core library; tested here directly.
#include "../../src/core/cloud_neighbours_internal.h"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace freeform_inspection {
namespace {

constexpr unsigned kSeed = 4242;
constexpr double kRadius = 0.05;  // a 100 mm ball, in metres
constexpr int kSphereCount = 20000;

std::string seedText(unsigned seed) {
  return "seed " + std::to_string(seed);
}

double quantile(std::vector<double> values, double q) {
  const auto rank = static_cast<std::ptrdiff_t>(q * double(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  return values[static_cast<std::size_t>(rank)];
}

double median(const std::vector<double>& values) {
  return quantile(values, 0.5);
}

std::vector<double> scaled(const std::vector<double>& values, double factor) {
  std::vector<double> result;
  for (const double v : values) {
    result.push_back(v * factor);
  }
  return result;
}

bool allFinite(const CurvatureResult& result) {
  const auto finite = [](double v) { return std::isfinite(v); };
  bool ok = std::all_of(result.mean.begin(), result.mean.end(), finite) &&
            std::all_of(result.area.begin(), result.area.end(), finite);
  for (const auto& n : result.normals) {
    ok = ok && n.allFinite();
  }
  return ok;
}

CurvatureResult curvature(const Points& points, const Points& normals, int k = 24) {
  CloudCurvatureConfig config;
  config.neighbours = k;
  return computeCloudCurvature(points, normals, config);
}

// Given normals only orient the PCA normals (curvature.h): the curvature depends on the points
// alone, like the CAD's. PCA normals belong to neighbourhood centroids, which lie closer together
// than the points, so the fitted curvature reads about 3 % small, the same on every surface.
constexpr double kPcaScale = 0.973;

TEST(CloudCurvature, SphereWithGivenNormalsHasMeanCurvatureOneOverR) {
  const analytic::Cloud sphere = analytic::sampleSphere(kRadius, kSphereCount, kSeed);
  const CurvatureResult result = curvature(sphere.points, sphere.normals);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.mean.size(), sphere.points.size());
  EXPECT_TRUE(result.gaussian.empty());  // documented: clouds give H only
  const std::vector<double> hr = scaled(result.mean, kRadius);
  // Measured: median 0.9733, 5–95 % band 0.891 … 1.029 (k = 24, 20k random points).
  EXPECT_NEAR(median(hr), kPcaScale, 0.005) << seedText(kSeed);
  EXPECT_GT(quantile(hr, 0.05), 0.85) << seedText(kSeed);
  EXPECT_LT(quantile(hr, 0.95), 1.07) << seedText(kSeed);
  for (std::size_t i = 0; i < sphere.points.size(); ++i) {
    ASSERT_GT(result.normals[i].dot(sphere.normals[i]), std::cos(3.0 * M_PI / 180.0))
        << "point " << i << ": oriented like the given normal, within 3°";
  }
}

TEST(CloudCurvature, SphereWithEstimatedNormalsIsOrientedOutwardAndHasOneOverR) {
  const analytic::Cloud sphere = analytic::sampleSphere(kRadius, kSphereCount, kSeed);
  const CurvatureResult result = curvature(sphere.points, Points());
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  std::size_t outward = 0;
  double worst_angle_cos = 1.0;
  for (std::size_t i = 0; i < sphere.points.size(); ++i) {
    const double cos_angle = result.normals[i].dot(sphere.normals[i]);
    outward += cos_angle > 0.0 ? 1 : 0;
    worst_angle_cos = std::min(worst_angle_cos, std::abs(cos_angle));
  }
  // Measured: all 20000 outward, worst PCA normal 1.7° off, median H·R 0.9733: a PCA normal
  // belongs to its neighbourhood's centroid, and overlapping neighbourhoods have centroids
  // closer together than the points, so normal changes read about 3 % small.
  EXPECT_GE(double(outward), 0.99 * kSphereCount) << seedText(kSeed);
  EXPECT_GT(worst_angle_cos, 0.999) << seedText(kSeed);  // PCA normals within 2.6°
  EXPECT_NEAR(median(scaled(result.mean, kRadius)), kPcaScale, 0.005) << seedText(kSeed);
}

TEST(CloudCurvature, AreaSumsToTheSphereSurface) {
  const analytic::Cloud sphere = analytic::sampleSphere(kRadius, kSphereCount, kSeed);
  const CurvatureResult result = curvature(sphere.points, sphere.normals);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  const double total = std::accumulate(result.area.begin(), result.area.end(), 0.0);
  const double exact = 4.0 * analytic::kPi * kRadius * kRadius;
  // π d_k²/k counts the point itself among the k, so for random (Poisson) sampling its
  // expectation is (k − 1)/k of the true area per point: −4.2 % for k = 24, measured 0.9579.
  EXPECT_NEAR(total / exact, 23.0 / 24.0, 0.01) << seedText(kSeed) << " ratio " << total / exact;
}

TEST(CloudCurvature, CylinderHasHalfTheCurvatureOfTheSphere) {
  const double length = 4.0 * kRadius;
  const analytic::Cloud cylinder = analytic::sampleCylinder(kRadius, length, 20000, kSeed);
  for (const bool given : {true, false}) {
    const CurvatureResult result = curvature(cylinder.points, given ? cylinder.normals : Points());
    ASSERT_TRUE(result.status.ok()) << result.status.message;
    // Measured 0.4885 with given and with estimated normals (~3 % small as on the sphere).
    EXPECT_NEAR(median(scaled(result.mean, kRadius)), 0.5 * kPcaScale, 0.005)
        << seedText(kSeed) << (given ? " given normals" : " estimated normals");
  }
}

TEST(CloudCurvature, PlaneHasZeroCurvature) {
  const double side = 0.2;
  const analytic::Cloud plane = analytic::samplePlane(side, 5000, kSeed);
  for (const bool given : {true, false}) {
    const CurvatureResult result = curvature(plane.points, given ? plane.normals : Points());
    ASSERT_TRUE(result.status.ok()) << result.status.message;
    double worst = 0.0;
    for (const double h : result.mean) {
      worst = std::max(worst, std::abs(h));
    }
    EXPECT_LT(worst * side, 1e-9) << seedText(kSeed);
  }
}

// Each point moved onto its neighbourhood's plane: the noise along the normal averages out
// (24 neighbours: about σ/√24 is left, plus the plane's own error), the position in the plane
// is kept.
TEST(CloudCurvature, PointsOnTheirNeighbourhoodPlaneLoseTheNoise) {
  const double side = 0.2;
  const double sigma = 0.001;
  analytic::Cloud plane = analytic::samplePlane(side, 20000, kSeed);
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (auto& p : plane.points) {
    p.z() += noise(rng);
  }
  const CurvatureResult result = curvature(plane.points, Points());
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.on_plane.size(), plane.points.size());
  double before = 0.0;
  double after = 0.0;
  double sideways = 0.0;
  for (std::size_t i = 0; i < plane.points.size(); ++i) {
    before += plane.points[i].z() * plane.points[i].z();
    after += result.on_plane[i].z() * result.on_plane[i].z();
    sideways += (result.on_plane[i] - plane.points[i]).head<2>().squaredNorm();
  }
  before = std::sqrt(before / static_cast<double>(plane.points.size()));
  after = std::sqrt(after / static_cast<double>(plane.points.size()));
  sideways = std::sqrt(sideways / static_cast<double>(plane.points.size()));
  std::printf("RMS along the normal %.3f σ before, %.3f σ after; sideways %.3f σ\n",
              before / sigma,
              after / sigma,
              sideways / sigma);
  EXPECT_NEAR(before, sigma, 0.05 * sigma);
  EXPECT_LT(after, 0.35 * sigma) << seedText(kSeed);
  EXPECT_LT(sideways, 0.3 * sigma);  // RMS: moved along the (nearly vertical) normal only
}

// A noisy sphere's points moved onto their neighbourhood's plane sit inside the sphere by about
// H·⟨|t|²⟩/2 (the plane cuts the bend); onto the neighbourhood's quadric they keep the sphere on
// average, most of the noise removed too. 100 neighbours of 20,000 points on a 50 mm ball at
// σ = 0.5 mm, measured (kSeed): mean −0.50 σ on the planes, −0.03 σ on the quadrics; spread
// 0.11 σ and 0.20 σ (six coefficients from 100 points against three).
TEST(CloudCurvature, PointsOnTheirNeighbourhoodQuadricKeepTheBendThePlaneCuts) {
  constexpr int kNeighbours = 100;
  const double sigma = 0.01 * kRadius;
  analytic::Cloud sphere = analytic::sampleSphere(kRadius, kSphereCount, kSeed);
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (std::size_t i = 0; i < sphere.points.size(); ++i) {
    sphere.points[i] += sphere.normals[i] * noise(rng);
  }
  internal::NeighbourTable table;
  CloudCurvatureConfig config;
  config.neighbours = kNeighbours;
  const CurvatureResult result =
      internal::computeCloudCurvature(sphere.points, Points(), config, kNeighbours, &table);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  const Points on_quadric =
      internal::ontoLocalQuadrics(sphere.points, result.normals, table, kNeighbours);
  ASSERT_EQ(on_quadric.size(), sphere.points.size());
  const auto offsets = [&](const Points& points) {
    double sum = 0.0;
    double squares = 0.0;
    for (const auto& p : points) {
      sum += p.norm() - kRadius;
      squares += (p.norm() - kRadius) * (p.norm() - kRadius);
    }
    const auto n = static_cast<double>(points.size());
    const double mean = sum / n;
    return std::make_pair(mean, std::sqrt(std::max(0.0, squares / n - mean * mean)));
  };
  const auto [plane_bias, plane_spread] = offsets(result.on_plane);
  const auto [quadric_bias, quadric_spread] = offsets(on_quadric);
  const auto [measured_bias, measured_spread] = offsets(sphere.points);
  std::printf(
      "distance to the sphere, mean / spread: measured %+.3f / %.3f σ, plane %+.3f / %.3f σ, "
      "quadric %+.3f / %.3f σ\n",
      measured_bias / sigma,
      measured_spread / sigma,
      plane_bias / sigma,
      plane_spread / sigma,
      quadric_bias / sigma,
      quadric_spread / sigma);
  EXPECT_LT(plane_bias, -0.2 * sigma) << seedText(kSeed);  // the plane cuts the bend
  EXPECT_LT(std::abs(quadric_bias), 0.1 * sigma) << seedText(kSeed);
  EXPECT_LT(quadric_spread, 0.4 * measured_spread) << seedText(kSeed);
}

// A wall thinner than the neighbourhood: each side's points have the other side's among their
// neighbours, with normals turned the other way. Those are left out of the quadric, so a side
// stays where it is instead of being drawn to the mid-plane (which the six coefficients cannot
// tell from a bend). And neighbours along one line cannot fix a quadric: the point goes onto
// the plane through their mean, with no NaN.
TEST(CloudCurvature, QuadricsKeepEachSideOfAThinWallAndFallBackOnALine) {
  constexpr int kNeighbours = 60;
  const double side = 0.1;
  const double wall = 0.002;  // 2 mm: the 60 neighbours reach ~5.5 mm on 4,000 points a side
  analytic::Cloud top = analytic::samplePlane(side, 4000, kSeed);
  const analytic::Cloud bottom = analytic::samplePlane(side, 4000, kSeed + 1);
  Points points;
  Points normals;
  for (const auto& p : top.points) {
    points.push_back(p + Eigen::Vector3d(0.0, 0.0, 0.5 * wall));
    normals.push_back(Eigen::Vector3d::UnitZ());
  }
  for (const auto& p : bottom.points) {
    points.push_back(p - Eigen::Vector3d(0.0, 0.0, 0.5 * wall));
    normals.push_back(-Eigen::Vector3d::UnitZ());
  }
  internal::NeighbourTable table;
  CloudCurvatureConfig config;
  config.neighbours = kNeighbours;
  const CurvatureResult result =
      internal::computeCloudCurvature(points, normals, config, kNeighbours, &table);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  std::size_t mixed = 0;  // neighbourhoods that hold both sides
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int* row = table.of(i);
    mixed += std::any_of(row,
                         row + kNeighbours,
                         [&](int j) { return points[std::size_t(j)].z() * points[i].z() < 0.0; })
                 ? 1
                 : 0;
  }
  const Points moved = internal::ontoLocalQuadrics(points, result.normals, table, kNeighbours);
  double worst = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    worst = std::max(worst, std::abs(moved[i].z() - points[i].z()));
  }
  std::printf("%zu of %zu neighbourhoods hold both sides; largest move %.2e m (wall %.0e m)\n",
              mixed,
              points.size(),
              worst,
              wall);
  EXPECT_GT(mixed, points.size() / 2);  // the case is the one described
  EXPECT_LT(worst, 1e-9);               // each side stays on its plane

  Points line;
  for (int i = 0; i < 100; ++i) {
    line.emplace_back(0.001 * i, 0.0, 0.0);
  }
  internal::NeighbourTable line_table = internal::nearestNeighbourTable(line, 12);
  const Points line_normals(line.size(), Eigen::Vector3d::UnitZ());
  const Points on_line = internal::ontoLocalQuadrics(line, line_normals, line_table, 12);
  for (std::size_t i = 0; i < line.size(); ++i) {
    ASSERT_TRUE(on_line[i].allFinite()) << "point " << i;
    EXPECT_LT((on_line[i] - line[i]).norm(), 1e-12) << "point " << i;
  }
}

// The edge of a block: a top face (z = 0, x ≤ 0, normal +z) and a side face (x = 0, z ≤ 0,
// normal +x), 50 × 100 mm and 4,000 points each, their exact normals given. Near the edge a point's
// neighbours hold the other face, which climbs over its tangent plane faster than a quadric can
// follow; left out (turned by more than 45°), each face stays on its plane. Kept, as they were up
// to 0.9.5 (only neighbours turned by more than 120° left out), the quadric rounded the edge and
// moved points near it by up to 3.6 mm (checked by building so).
TEST(CloudCurvature, QuadricsKeepEachFaceOfAnEdgeOnItsPlane) {
  constexpr int kNeighbours = 60;
  const double side = 0.1;
  const analytic::Cloud top = analytic::samplePlane(side, 4000, kSeed);
  const analytic::Cloud wall = analytic::samplePlane(side, 4000, kSeed + 1);
  Points points;
  Points normals;
  for (const auto& p : top.points) {  // x in [-side, 0]
    points.emplace_back(0.5 * (p.x() - 0.5 * side), p.y(), 0.0);
    normals.push_back(Eigen::Vector3d::UnitZ());
  }
  for (const auto& p : wall.points) {  // z in [-side, 0]
    points.emplace_back(0.0, p.y(), 0.5 * (p.x() - 0.5 * side));
    normals.push_back(Eigen::Vector3d::UnitX());
  }
  const internal::NeighbourTable table = internal::nearestNeighbourTable(points, kNeighbours);
  std::size_t across = 0;  // neighbourhoods that reach the other face
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int* row = table.of(i);
    across += std::any_of(row,
                          row + kNeighbours,
                          [&](int j) { return normals[std::size_t(j)].dot(normals[i]) < 0.5; })
                  ? 1
                  : 0;
  }
  const Points moved = internal::ontoLocalQuadrics(points, normals, table, kNeighbours);
  double worst = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    worst = std::max(worst, std::abs(normals[i].dot(moved[i] - points[i])));
  }
  std::printf("%zu of %zu neighbourhoods reach the other face; largest move %.2e m\n",
              across,
              points.size(),
              worst);
  EXPECT_GT(across, points.size() / 20);  // the case is the one described
  EXPECT_LT(worst, 1e-9);                 // each face stays on its plane
}

TEST(CloudCurvature, SaddleHasZeroMeanCurvatureAtTheOriginAndMatchesEverywhere) {
  const double scale = 0.1;  // principal curvatures ±10 /m at the origin
  analytic::Cloud saddle = analytic::sampleSaddle(scale, 0.1, 10000, kSeed);
  saddle.points.emplace_back(0.0, 0.0, 0.0);
  saddle.normals.push_back(Eigen::Vector3d::UnitZ());
  const CurvatureResult result = curvature(saddle.points, saddle.normals);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  // Measured |H|·s = 0.032 at the origin (k1 = −k2 = 10 /m, so a 3 % error on one principal
  // direction), 95th percentile of the error 0.114 elsewhere (the saddle's slopes tilt the
  // neighbourhoods, and PCA normals average over them).
  EXPECT_LT(std::abs(result.mean.back()) * scale, 0.05) << seedText(kSeed);
  std::vector<double> error;
  for (std::size_t i = 0; i < saddle.points.size(); ++i) {
    const Eigen::Vector3d& p = saddle.points[i];
    if (std::max(std::abs(p.x()), std::abs(p.y())) < 0.04) {  // away from the open border
      error.push_back(
          std::abs(result.mean[i] - analytic::saddleMeanCurvature(p.x(), p.y(), scale)) * scale);
    }
  }
  EXPECT_LT(quantile(error, 0.95), 0.15) << seedText(kSeed);
}

TEST(CloudCurvature, InwardGivenNormalsFlipTheSign) {
  analytic::Cloud sphere = analytic::sampleSphere(kRadius, kSphereCount, kSeed);
  for (auto& n : sphere.normals) {
    n = -n;
  }
  const CurvatureResult result = curvature(sphere.points, sphere.normals);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_NEAR(median(scaled(result.mean, kRadius)), -kPcaScale, 0.005) << seedText(kSeed);
}

// Points without a normal (zero vector) are oriented from their neighbours that have one.
TEST(CloudCurvature, MissingNormalsAreOrientedFromTheGivenOnes) {
  analytic::Cloud sphere = analytic::sampleSphere(kRadius, 5000, kSeed);
  Points normals = sphere.normals;
  for (std::size_t i = 0; i < normals.size(); i += 3) {
    normals[i] = -Eigen::Vector3d::Zero();
  }
  // Inward given normals: the propagation must follow them, not the centroid vote.
  for (auto& n : normals) {
    n = -n;
  }
  const CurvatureResult result = curvature(sphere.points, normals);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  for (std::size_t i = 0; i < normals.size(); ++i) {
    ASSERT_LT(result.normals[i].dot(sphere.normals[i]), -0.99) << seedText(kSeed) << " " << i;
  }
}

// Noise of 0.5 % of the diameter along the normals (σ = 0.5 mm against a 1.25 mm sample
// spacing): the per-point estimator spreads, measured 10–90 % band of H·R 2.0 wide with k = 24
// and median 0.96 (PCA normals average the noise over the neighbourhood). The descriptor then
// averages over geodesic balls.
TEST(CloudCurvature, NoiseSpreadsThePerPointEstimateButNotTheMedian) {
  analytic::Cloud sphere = analytic::sampleSphere(kRadius, kSphereCount, kSeed);
  std::mt19937 rng(kSeed + 1);
  std::normal_distribution<double> noise(0.0, 0.005 * 2.0 * kRadius);
  for (std::size_t i = 0; i < sphere.points.size(); ++i) {
    sphere.points[i] += noise(rng) * sphere.normals[i];
  }
  const CurvatureResult result = curvature(sphere.points, Points());
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  const std::vector<double> hr = scaled(result.mean, kRadius);
  const double spread = quantile(hr, 0.9) - quantile(hr, 0.1);
  RecordProperty("h_r_median", std::to_string(median(hr)));
  RecordProperty("h_r_spread_10_90", std::to_string(spread));
  EXPECT_NEAR(median(hr), 0.96, 0.05) << seedText(kSeed + 1);
  EXPECT_GT(spread, 1.0) << seedText(kSeed + 1) << ": noise should spread per-point H";
  EXPECT_LT(spread, 4.0) << seedText(kSeed + 1);
}

TEST(CloudCurvature, FewerPointsThanNeighboursIsDegenerate) {
  const analytic::Cloud sphere = analytic::sampleSphere(kRadius, 5, kSeed);
  EXPECT_EQ(curvature(sphere.points, Points(), 24).status.code, StatusCode::kDegenerateInput);
}

TEST(CloudCurvature, NonFiniteOrMismatchedInputIsInvalid) {
  analytic::Cloud sphere = analytic::sampleSphere(kRadius, 100, kSeed);
  EXPECT_EQ(curvature(Points(), Points()).status.code, StatusCode::kInvalidInput);
  Points fewer(sphere.normals.begin(), sphere.normals.end() - 1);
  EXPECT_EQ(curvature(sphere.points, fewer).status.code, StatusCode::kInvalidInput);
  EXPECT_EQ(curvature(sphere.points, Points(), 5).status.code, StatusCode::kInvalidInput);
  Points bad_normals = sphere.normals;
  bad_normals[9] = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(curvature(sphere.points, bad_normals).status.code, StatusCode::kInvalidInput);
  sphere.points[17].y() = std::numeric_limits<double>::quiet_NaN();
  const CurvatureResult result = curvature(sphere.points, Points());
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_NE(result.status.message.find("17"), std::string::npos) << result.status.message;
}

TEST(CloudCurvature, IdenticalPointsGiveZeroCurvatureAndNoNan) {
  const Points same(100, Eigen::Vector3d(0.1, 0.2, 0.3));
  const CurvatureResult result = curvature(same, Points());
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput);
  ASSERT_EQ(result.mean.size(), same.size());
  EXPECT_TRUE(allFinite(result));
  for (std::size_t i = 0; i < same.size(); ++i) {
    EXPECT_EQ(result.mean[i], 0.0);
    EXPECT_EQ(result.area[i], 0.0);
  }
}

TEST(CloudCurvature, CollinearPointsGiveZeroCurvatureAndNoNan) {
  Points line;
  for (int i = 0; i < 50; ++i) {
    line.emplace_back(0.001 * i, 0.002 * i, -0.001 * i);
  }
  const CurvatureResult result = curvature(line, Points());
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput);
  EXPECT_TRUE(allFinite(result));
  for (const double h : result.mean) {
    EXPECT_EQ(h, 0.0);
  }
}

// A few degenerate points in a good cloud: they get H = 0, the rest is unaffected.
TEST(CloudCurvature, DuplicateClusterInsideAGoodCloudGetsZeroCurvature) {
  analytic::Cloud sphere = analytic::sampleSphere(kRadius, 2000, kSeed);
  const Eigen::Vector3d far(1.0, 1.0, 1.0);
  for (int i = 0; i < 30; ++i) {
    sphere.points.push_back(far);
  }
  const CurvatureResult result = curvature(sphere.points, Points());
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_TRUE(allFinite(result));
  EXPECT_EQ(result.mean.back(), 0.0);
  std::vector<double> hr(result.mean.begin(), result.mean.begin() + 2000);
  EXPECT_NEAR(median(scaled(hr, kRadius)), 1.0, 0.03) << seedText(kSeed);
}

TEST(CloudCurvature, OrganizedSaddleWithSensorNormalsMatchesTheAnalyticCurvature) {
  const double scale = 0.2;
  const analytic::Pinhole camera{80, 60, 200.0};
  const analytic::Cloud saddle =
      analytic::finitePart(analytic::organizedSaddle(camera, 1.0, scale));
  ASSERT_EQ(saddle.points.size(), 80u * 60u);
  const CurvatureResult result = curvature(saddle.points, saddle.normals);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  std::vector<double> error;
  for (std::size_t i = 0; i < saddle.points.size(); ++i) {
    const Eigen::Vector3d& p = saddle.points[i];
    // Sensor-facing normals are the −z side: the sign flips relative to saddleMeanCurvature.
    const double expected = -analytic::saddleMeanCurvature(p.x(), p.y(), scale);
    error.push_back(std::abs(result.mean[i] - expected) * scale);
  }
  EXPECT_LT(median(error), 0.005);  // measured 0.0015 (95th percentile 0.008)
}

// Rows of the shared table must be exactly PointIndex::nearest, whichever path (grid or kd-tree)
// answered them: a random sphere, a regular grid full of exact ties, and duplicated points.
TEST(NeighbourTable, EveryRowIsTheKdTreeAnswer) {
  analytic::Cloud sphere = analytic::sampleSphere(kRadius, kSphereCount, kSeed);
  Points grid;
  for (int i = 0; i < 90; ++i) {
    for (int j = 0; j < 90; ++j) {
      grid.emplace_back(0.001 * i, 0.001 * j, 0.0);
    }
  }
  Points duplicated = sphere.points;
  for (std::size_t i = 0; i < 200; ++i) {
    duplicated.push_back(sphere.points[i * 13]);
  }
  Points sparse(sphere.points.begin(), sphere.points.begin() + 3000);  // below the grid size
  // A shell 4 spacings thick (noise wider than the spacing): three-dimensional at the scale of
  // the neighbours, where the grid's cubes are sized by the cube root of the density.
  Points slab = sphere.points;
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 0.005);
  for (auto& p : slab) {
    p *= 1.0 + noise(rng) / kRadius;
  }
  for (const Points* points : {&sphere.points, &grid, &duplicated, &sparse, &slab}) {
    const PointIndex index(*points);
    for (const int k : {9, 24}) {
      // The misses answered by a kd-tree built inside, or by the caller's index.
      for (const PointIndex* given : {static_cast<const PointIndex*>(nullptr), &index}) {
        const internal::NeighbourTable table = internal::nearestNeighbourTable(*points, k, given);
        ASSERT_EQ(table.k, k);
        std::size_t differing = 0;
        for (std::size_t i = 0; i < points->size(); ++i) {
          const std::vector<Neighbour> expected = index.nearest((*points)[i], k);
          for (int j = 0; j < k; ++j) {
            differing += expected[std::size_t(j)].index == table.of(i)[j] ? 0 : 1;
          }
        }
        EXPECT_EQ(differing, 0u) << points->size() << " points, k = " << k
                                 << (given != nullptr ? ", caller's index" : "");
      }
    }
  }
  const Points tiny(sphere.points.begin(), sphere.points.begin() + 40);
  EXPECT_EQ(internal::nearestNeighbourTable(tiny, 50).k, 40);  // clamped to the set
  EXPECT_EQ(internal::nearestNeighbourTable(Points(), 24).k, 0);
}

// cloudEdges: each accepted kNN pair once, as (lower, higher), sorted; same as the definition.
TEST(CloudEdges, AreTheAcceptedKnnPairsOnce) {
  const analytic::Cloud sphere = analytic::sampleSphere(kRadius, kSphereCount, kSeed);
  Points normals = sphere.normals;
  for (std::size_t i = 0; i < normals.size(); i += 7) {
    normals[i] = -normals[i];  // some pairs face opposite sides
  }
  const double max_length = 0.0015;
  const std::vector<SurfaceEdge> edges = cloudEdges(sphere.points, normals, 8, max_length);
  const PointIndex index(sphere.points);
  std::vector<SurfaceEdge> expected;
  for (std::size_t i = 0; i < sphere.points.size(); ++i) {
    for (const Neighbour& nb : index.nearest(sphere.points[i], 9)) {
      const auto j = static_cast<std::size_t>(nb.index);
      if (j != i && nb.squared_distance <= max_length * max_length &&
          normals[i].dot(normals[j]) > 0.0) {
        expected.emplace_back(int(std::min(i, j)), int(std::max(i, j)));
      }
    }
  }
  std::sort(expected.begin(), expected.end());
  expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
  EXPECT_EQ(edges, expected);
}

#ifdef _OPENMP
TEST(CloudCurvature, ResultIsBitIdenticalForAnyThreadCount) {
  const analytic::Cloud sphere = analytic::sampleSphere(kRadius, 5000, kSeed);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const CurvatureResult serial = curvature(sphere.points, Points());
  omp_set_num_threads(3);
  const CurvatureResult parallel = curvature(sphere.points, Points());
  omp_set_num_threads(threads);
  EXPECT_EQ(serial.mean, parallel.mean);
  EXPECT_EQ(serial.area, parallel.area);
  EXPECT_EQ(serial.normals, parallel.normals);
}
#endif

}  // namespace
}  // namespace freeform_inspection
