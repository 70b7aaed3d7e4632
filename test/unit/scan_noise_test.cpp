// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/scan_noise.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace freeform_inspection {
namespace {

// A square plate 0.2 m wide, sampled at random, with Gaussian noise σ along z.
Points noisyPlate(std::size_t count, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> along(0.0, 0.2);
  std::normal_distribution<double> noise(0.0, sigma);
  Points points;
  for (std::size_t i = 0; i < count; ++i) {
    const double x = along(rng);
    const double y = along(rng);
    points.emplace_back(x, y, noise(rng));
  }
  return points;
}

// A sphere of radius R sampled uniformly, each point moved by Gaussian noise σ along its normal.
Points noisySphere(std::size_t count, double radius, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, sigma);
  Points points;
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector3d direction =
        Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    points.push_back(direction * (radius + noise(rng)));
  }
  return points;
}

TEST(ScanNoise, PlateNoiseIsMeasuredWhateverTheDensity) {
  const double sigma = 0.0002;
  // 20k points are all indexed; 400k are measured on a 50k subset: the same σ either way.
  for (const std::size_t count : {std::size_t{20000}, std::size_t{400000}}) {
    const double measured = estimateScanNoise(noisyPlate(count, sigma, 7), 0.005);
    EXPECT_NEAR(measured, sigma, 0.05 * sigma) << count << " points, seed 7";
  }
  EXPECT_NEAR(estimateScanNoise(noisyPlate(20000, 0.0, 7), 0.005), 0.0, 1e-12);
  EXPECT_EQ(estimateScanNoise(noisyPlate(10, sigma, 7), 0.005), 0.0);   // too few to fit
  EXPECT_EQ(estimateScanNoise(noisyPlate(20000, sigma, 7), 0.0), 0.0);  // no neighbourhood
}

// The curvature inside the neighbourhood is not noise: a plane fit over a 10 mm ball on a
// 50 mm sphere would report its sagitta, about 0.1 mm RMS; the quadric reports almost nothing.
TEST(ScanNoise, CurvatureIsNotCountedAsNoise) {
  const double radius = 0.05;
  EXPECT_LT(estimateScanNoise(noisySphere(30000, radius, 0.0, 3), 0.01), 2e-6);
  const double sigma = 0.0002;
  EXPECT_NEAR(estimateScanNoise(noisySphere(30000, radius, sigma, 3), 0.01), sigma, 0.08 * sigma);
}

// Noise over half as wide as the radius it is measured over fills the neighbourhood (the
// pipeline's radius is 2 r_1, and 2 % noise on the diagonal is 1.2 r_1): the estimate is
// taken again over a radius that sees through it. σ = 3 mm measured from a 5 mm radius.
TEST(ScanNoise, NoiseWiderThanTheRadiusWidensIt) {
  const double sigma = 0.003;
  const double measured = estimateScanNoise(noisySphere(30000, 0.1, sigma, 5), 0.005);
  EXPECT_NEAR(measured, sigma, 0.12 * sigma);
}

// A thin wall: the two faces of a 2 mm plate 50 mm wide, 30k points a face (spacing 0.3 mm),
// each face with 0.03 mm of noise. A 5 mm ball spans both faces and reads about half the
// thickness (1 mm); the small first ball (32 neighbours, 0.7 mm) stays on one face.
TEST(ScanNoise, AThinWallIsNotReadAsNoise) {
  const double sigma = 0.00003;
  Points wall;
  for (const unsigned face : {9u, 10u}) {
    for (const Eigen::Vector3d& p : noisyPlate(30000, sigma, face)) {
      wall.emplace_back(0.25 * p.x(), 0.25 * p.y(), p.z() + (face == 10u ? 0.002 : 0.0));
    }
  }
  EXPECT_NEAR(estimateScanNoise(wall, 0.005), sigma, 0.1 * sigma);
}

}  // namespace
}  // namespace freeform_inspection
