// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// Signed deviation against surfaces whose distances are known exactly (plane, box) or to the
// tessellation's sagitta (sphere); statistics against hand-computed values; coverage of a box
// scanned on one face.
#include "freeform_inspection/deviation.h"

#include <cmath>
#include <limits>
#include <random>

#include "analytic_shapes.h"
#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/model.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(Deviation, PlaneSignedDistanceIsExactAndTheBorderIsRespected) {
  // 0.2 m square sheet at z = 0, normals +z (an open surface: a stamping).
  const Model plane(test::planarGrid(0.2, 20), "plane", "test");
  const Points points = {{0.01, 0.02, 0.003},    // above: excess material
                         {-0.05, 0.07, -0.002},  // below: missing material
                         {0.0999, 0.0, 0.001},   // above, just inside the border
                         {0.15, 0.0, 0.001},     // past the border: no nominal surface
                         {0.0, 0.0, 0.5}};       // beyond the reach
  const SurfaceDistances d = measureDeviation(plane, points, 0.05);
  EXPECT_NEAR(d.deviation[0], 0.003, 1e-9);
  EXPECT_NEAR(d.deviation[1], -0.002, 1e-9);
  EXPECT_NEAR(d.deviation[2], 0.001, 1e-9);
  EXPECT_TRUE(std::isnan(d.deviation[3]));
  EXPECT_TRUE(std::isnan(d.deviation[4]));
  EXPECT_NEAR(d.normals[0].z(), 1.0, 1e-12);
  EXPECT_EQ(d.normals[3].squaredNorm(), 0.0);
}

TEST(Deviation, BoxDistancesAtFacesEdgesAndCornersAreExact) {
  const Eigen::Vector3d half(0.05, 0.1, 0.15);
  const Model box(test::makeBox(half), "box", "test");
  const Points points = {{0.06, 0.0, 0.0},         // 10 mm outside the +x face
                         {0.0, -0.09, 0.02},       // 10 mm inside the -y face
                         {0.053, 0.104, 0.0},      // outside the +x+y edge: 5 mm
                         {-0.051, -0.102, 0.152},  // outside a corner: 3 mm
                         {0.0, 0.0, 0.0}};         // centre: 50 mm inside (nearest: x faces)
  const SurfaceDistances d = measureDeviation(box, points, 1.0);
  EXPECT_NEAR(d.deviation[0], 0.010, 1e-9);
  EXPECT_NEAR(d.deviation[1], -0.010, 1e-9);
  EXPECT_NEAR(d.deviation[2], 0.005, 1e-9);
  EXPECT_NEAR(d.deviation[3], std::sqrt(1e-6 + 4e-6 + 4e-6), 1e-9);
  EXPECT_NEAR(d.deviation[4], -0.05, 1e-9);
}

// A 1 mm plate seen from above: a point dented 0.8 mm into it lies nearer the bottom face,
// which the closest surface alone would read as -0.2 mm, a quarter of the dent (and a point
// pushed through the wall as a bump). With the point's outward
// normal it reads against its own face, -0.8 mm; points their closest face explains (above the
// top, beside the +x side with its normal) or with a zero normal are as without normals.
TEST(Deviation, ANormalReadsAThinWallDentedPastItsMiddleAgainstItsOwnSide) {
  const Model plate(test::makeBox(Eigen::Vector3d(0.02, 0.015, 0.0005)), "plate", "test");
  const Eigen::Vector3d up(0.0, 0.0, 1.0);
  const Points points = {{0.0, 0.0, -0.0003},      // top face dented by 0.8 mm
                         {0.005, 0.0, 0.0007},     // 0.2 mm above the top face
                         {0.0, 0.0, -0.0003},      // the dented point without a normal
                         {0.0202, 0.0, -0.0003}};  // 0.2 mm beside the +x side
  const Points normals = {up, up, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()};
  const SurfaceDistances plain = measureDeviation(plate, points, 0.01);
  const SurfaceDistances facing = measureDeviation(plate, points, 0.01, normals, 80.0);
  EXPECT_NEAR(plain.deviation[0], -0.0002, 1e-9);
  EXPECT_NEAR(facing.deviation[0], -0.0008, 1e-9);
  EXPECT_NEAR(facing.normals[0].z(), 1.0, 1e-12);
  for (std::size_t i = 1; i < points.size(); ++i) {
    EXPECT_EQ(facing.deviation[i], plain.deviation[i]) << "point " << i;
    EXPECT_EQ(facing.faces[i], plain.faces[i]) << "point " << i;
  }
  EXPECT_NEAR(facing.deviation[1], 0.0002, 1e-9);
  EXPECT_NEAR(facing.deviation[3], 0.0002, 1e-9);
  // 180 degrees asks for the closest surface whatever its way.
  EXPECT_EQ(measureDeviation(plate, points, 0.01, normals, 180.0).deviation[0], plain.deviation[0]);
  // Normals most of the scan turns into the material (an inward winding) are not used.
  Points many(20, Eigen::Vector3d(0.0, 0.0, 0.0006));
  Points inward(20, -up);
  many.push_back(points[0]);
  inward.push_back(up);
  const SurfaceDistances ignored = measureDeviation(plate, many, 0.01, inward, 80.0);
  EXPECT_NEAR(ignored.deviation.back(), -0.0002, 1e-9);
  EXPECT_NEAR(ignored.deviation.front(), 0.0001, 1e-9);
}

TEST(Deviation, SphereWithinTheTessellationSagitta) {
  const double radius = 0.1;
  const TriangleMesh mesh = test::icosphere(radius, 5);
  // A facet's corners lie on the sphere; its circumradius is at most e / √3 for the longest
  // edge e, so a point at radius ρ is within ρ (1 − cos θ), θ = e / (√3 R), of its true
  // distance.
  double edge = 0.0;
  for (const auto& f : mesh.faces) {
    edge = std::max(edge, (mesh.vertices[f[0]] - mesh.vertices[f[1]]).norm());
  }
  const double sagitta = radius * (1.0 - std::cos(edge / (std::sqrt(3.0) * radius)));
  const Model sphere(mesh, "sphere", "test");
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> offset(-0.01, 0.01);
  Points points;
  std::vector<double> truth;
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d direction =
        Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    truth.push_back(offset(rng));
    points.push_back((radius + truth.back()) * direction);
  }
  const SurfaceDistances d = measureDeviation(sphere, points, 0.05);
  std::printf("sphere R = %.3f, sagitta %.3g m, seed 7\n", radius, sagitta);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(d.deviation[i], truth[i], sagitta * (radius + std::abs(truth[i])) / radius + 1e-7)
        << i;
  }
}

TEST(Deviation, InwardWoundCadGivesTheSameSigns) {
  // A CAD exported inside out is re-wound on load, so "positive = excess material" holds.
  const Model outward(test::icosphere(0.1, 3), "out", "test");
  const Model inward(test::flipped(test::icosphere(0.1, 3)), "in", "test");
  EXPECT_EQ(inward.orientation().reversed_components, 1u);
  const Points points = {{0.11, 0.0, 0.0}, {0.0, 0.0, -0.095}};
  const auto a = measureDeviation(outward, points, 0.05).deviation;
  const auto b = measureDeviation(inward, points, 0.05).deviation;
  EXPECT_GT(a[0], 0.0);
  EXPECT_LT(a[1], 0.0);
  EXPECT_FLOAT_EQ(a[0], b[0]);
  EXPECT_FLOAT_EQ(a[1], b[1]);
}

TEST(Deviation, StatisticsMatchHandComputedValues) {
  // 20 values: -5..14 mm, plus 3 unmatched.
  std::vector<float> deviation;
  for (int i = -5; i < 15; ++i) {
    deviation.push_back(static_cast<float>(i) * 1e-3F);
  }
  deviation.insert(deviation.end(), {kNaN, kNaN, kNaN});
  ToleranceConfig tolerance;
  tolerance.upper = 0.0065;   // -5..6 mm inside: 12 of 20
  tolerance.lower = -0.0045;  // -5 mm outside: 11 of 20
  const DeviationStatistics s = summarizeDeviation(deviation, tolerance, 10);
  EXPECT_EQ(s.evaluated, 20u);
  EXPECT_EQ(s.unmatched, 3u);
  EXPECT_NEAR(s.mean, 4.5e-3, 1e-9);
  double sum2 = 0.0;
  for (int i = -5; i < 15; ++i) {
    sum2 += (i * 1e-3) * (i * 1e-3);
  }
  EXPECT_NEAR(s.rms, std::sqrt(sum2 / 20.0), 1e-9);
  EXPECT_NEAR(s.std, std::sqrt(sum2 / 20.0 - 4.5e-3 * 4.5e-3), 1e-9);
  EXPECT_NEAR(s.min, -5e-3, 1e-9);
  EXPECT_NEAR(s.max, 14e-3, 1e-9);
  EXPECT_NEAR(s.p50, 5e-3, 1e-9);   // nearest rank of 9.5 → index 10
  EXPECT_NEAR(s.p5, -4e-3, 1e-9);   // rank 0.95 → index 1
  EXPECT_NEAR(s.p95, 13e-3, 1e-9);  // rank 18.05 → index 18
  EXPECT_NEAR(s.in_tolerance_fraction, 11.0 / 20.0, 1e-12);
  ASSERT_EQ(s.histogram_counts.size(), 10u);
  ASSERT_EQ(s.histogram_edges.size(), 11u);
  std::size_t total = 0;
  for (const auto c : s.histogram_counts) {
    total += c;
  }
  EXPECT_EQ(total, 20u);
  EXPECT_NEAR(s.histogram_edges.front(), -s.histogram_edges.back(), 1e-15);
  EXPECT_GE(s.histogram_edges.back(), 14e-3 - 1e-9);  // reaches the bulk of the data
}

TEST(Deviation, CoverageOfABoxScannedOnOneFace) {
  const Eigen::Vector3d half(0.05, 0.1, 0.15);
  const Model box(test::makeBox(half), "box", "test");
  Points top;  // the +z face, 1 mm grid
  for (double x = -0.05; x <= 0.05; x += 0.001) {
    for (double y = -0.1; y <= 0.1; y += 0.001) {
      top.emplace_back(x, y, 0.15);
    }
  }
  const double face = 0.1 * 0.2;
  const double total = 2.0 * (0.1 * 0.2 + 0.1 * 0.3 + 0.2 * 0.3);
  const double coverage = surfaceCoverage(box, top, box.cellSize());
  std::printf(
      "coverage %.4f, expected %.4f (cell %.4f m)\n", coverage, face / total, box.cellSize());
  // Cells on the side faces within one cell of the top edge count too: a band of one cell.
  const double band = 2.0 * (0.1 + 0.2) * box.cellSize() / total;
  EXPECT_GT(coverage, face / total - 0.01);
  EXPECT_LT(coverage, face / total + band + 0.01);
  EXPECT_NEAR(
      surfaceCoverage(box, test::sampleBoxSurface(half, 120000, 3), box.cellSize()), 1.0, 0.01);
}

}  // namespace
}  // namespace freeform_inspection
