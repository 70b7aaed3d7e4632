// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// Mesh curvature (computeMeshCurvature, paper eq. 2, 3, 4–5) against analytic surfaces: plane,
// icosphere, cylinder, saddle, torus; orientation, noise (paper §4.1) and degenerate input.
// The bounds are the measured errors with a margin; docs/descriptors.md lists the measurements.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "analytic_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/curvature.h"
#include "freeform_inspection/mesh.h"
#include "freeform_inspection/mesh_adjacency.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr MeanCurvatureMethod kAngle = MeanCurvatureMethod::kAngleBased;
constexpr MeanCurvatureMethod kCotangent = MeanCurvatureMethod::kCotangent;

CurvatureResult curvature(const TriangleMesh& mesh, MeanCurvatureMethod method) {
  const MeshAdjacency adjacency = buildMeshAdjacency(mesh.faces, mesh.vertices.size());
  MeshCurvatureConfig config;
  config.method = method;
  return computeMeshCurvature(mesh.vertices, mesh.faces, adjacency, config);
}

double quantile(std::vector<double> values, double q) {
  const auto k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

double median(const std::vector<double>& values) {
  return quantile(values, 0.5);
}

double sum(const std::vector<double>& values) {
  double total = 0.0;
  for (double v : values) {
    total += v;
  }
  return total;
}

double sumOfProducts(const std::vector<double>& a, const std::vector<double>& b) {
  double total = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    total += a[i] * b[i];
  }
  return total;
}

double standardDeviation(const std::vector<double>& values) {
  const double mean = sum(values) / static_cast<double>(values.size());
  double squares = 0.0;
  for (double v : values) {
    squares += (v - mean) * (v - mean);
  }
  return std::sqrt(squares / static_cast<double>(values.size()));
}

// |value · scale − target| per vertex.
std::vector<double> errors(const std::vector<double>& values, double scale, double target) {
  std::vector<double> out;
  for (double v : values) {
    out.push_back(std::abs(v * scale - target));
  }
  return out;
}

// ---------------------------------------------------------------------------------- plane ---

TEST(CurvatureMeshPlane, JitteredGridHasZeroMeanCurvatureWithBothMethods) {
  constexpr unsigned kSeed = 4242;
  SCOPED_TRACE("jitter seed " + std::to_string(kSeed));
  const TriangleMesh grid = test::planarGrid(1.0, 20, 0.3, kSeed);
  for (const auto method : {kAngle, kCotangent}) {
    const CurvatureResult result = curvature(grid, method);
    ASSERT_TRUE(result.status.ok()) << result.status.message;
    for (std::size_t v = 0; v < grid.vertices.size(); ++v) {
      ASSERT_NEAR(result.mean[v], 0.0, 1e-12) << "vertex " << v;
      ASSERT_NEAR((result.normals[v] - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-12);
    }
    EXPECT_NEAR(sum(result.area), 1.0, 1e-12);
  }
}

TEST(CurvatureMeshPlane, AngleDeficitIsZeroInsideAndGaussBonnetHoldsWithBoundary) {
  constexpr unsigned kSeed = 77;
  SCOPED_TRACE("jitter seed " + std::to_string(kSeed));
  const TriangleMesh grid = test::planarGrid(2.0, 16, 0.3, kSeed);
  const CurvatureResult result = curvature(grid, kAngle);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  const std::size_t corner = 16;  // (i = 0, j = n): one right-angled corner
  for (std::size_t v = 0; v < grid.vertices.size(); ++v) {
    if (v != 0 && v != corner && v != grid.vertices.size() - 1 && v != grid.vertices.size() - 17) {
      ASSERT_NEAR(result.gaussian[v] * result.area[v], 0.0, 1e-12) << "vertex " << v;
    }
  }
  // Boundary deficit π − Σθ: the four corners turn by π/2 each, 2π = 2π χ(disc) in total.
  EXPECT_NEAR(result.gaussian[corner] * result.area[corner], kPi / 2.0, 1e-12);
  EXPECT_NEAR(sumOfProducts(result.gaussian, result.area), 2.0 * kPi, 1e-9);
}

// --------------------------------------------------------------------------------- sphere ---

struct SphereRow {
  int subdivisions;
  double angle_median_bound;      // median |H·R − 1|, angle-based
  double cotangent_median_bound;  // median |H·R − 1|, cotangent
  double gaussian_median_bound;   // median |K·R² − 1|
  double area_deficit_bound;      // 1 − Σ area / (4πR²)
};

// Measured (R = 2): see docs/descriptors.md. The H and K bounds are about twice the
// measurement; the area deficit is pure geometry (≈ 4× smaller per subdivision).
constexpr SphereRow kSphereRows[] = {
    {2, 5e-3, 3e-5, 1.8e-2, 2e-2},
    {3, 3e-3, 7e-6, 4.5e-3, 5e-3},
    {4, 1e-3, 1e-6, 1.6e-3, 1.25e-3},
};

TEST(CurvatureMeshSphere, ErrorShrinksWithTessellation) {
  constexpr double kRadius = 2.0;
  for (const SphereRow& row : kSphereRows) {
    const TriangleMesh sphere = test::icosphere(kRadius, row.subdivisions);
    const CurvatureResult angle = curvature(sphere, kAngle);
    const CurvatureResult cotangent = curvature(sphere, kCotangent);
    ASSERT_TRUE(angle.status.ok() && cotangent.status.ok());
    const double angle_error = median(errors(angle.mean, kRadius, 1.0));
    const double cotangent_error = median(errors(cotangent.mean, kRadius, 1.0));
    const double gaussian_error = median(errors(angle.gaussian, kRadius * kRadius, 1.0));
    const double deficit = 1.0 - sum(angle.area) / (4.0 * kPi * kRadius * kRadius);
    std::printf(
        "icosphere s=%d V=%zu: median|HR-1| angle %.2e cotangent %.2e, max angle %.3f, "
        "median|KR^2-1| %.2e, area deficit %.2e\n",
        row.subdivisions,
        sphere.vertices.size(),
        angle_error,
        cotangent_error,
        quantile(errors(angle.mean, kRadius, 1.0), 1.0),
        gaussian_error,
        deficit);
    SCOPED_TRACE("subdivisions " + std::to_string(row.subdivisions));
    EXPECT_LT(angle_error, row.angle_median_bound);
    EXPECT_LT(cotangent_error, row.cotangent_median_bound);
    EXPECT_LT(gaussian_error, row.gaussian_median_bound);
    EXPECT_GT(deficit, 0.0);  // the inscribed polyhedron is smaller than the sphere
    EXPECT_LT(deficit, row.area_deficit_bound);
    EXPECT_NEAR(
        sum(angle.area), analyzeTopology(sphere).area, 1e-12 * analyzeTopology(sphere).area);
  }
}

TEST(CurvatureMeshSphere, GaussBonnetIsExact) {
  for (int subdivisions = 0; subdivisions <= 5; ++subdivisions) {
    const CurvatureResult result = curvature(test::icosphere(0.3, subdivisions), kAngle);
    ASSERT_TRUE(result.status.ok());
    EXPECT_NEAR(sumOfProducts(result.gaussian, result.area), 4.0 * kPi, 1e-9)
        << "subdivisions " << subdivisions;
  }
}

TEST(CurvatureMeshSphere, NormalsPointOutward) {
  const TriangleMesh sphere = test::icosphere(1.5, 3);
  const CurvatureResult result = curvature(sphere, kAngle);
  for (std::size_t v = 0; v < sphere.vertices.size(); ++v) {
    ASSERT_NEAR(result.normals[v].dot(sphere.vertices[v].normalized()), 1.0, 1e-3);
  }
}

// The 12 valence-5 vertices of an icosphere stay off by the same factor at any resolution: the
// barycentric A/3 of eq. 2–3 is 14.6 % smaller than the region their edges' curvature belongs
// to (the Voronoi area of the 72°-apex fan). The cotangent method's mixed area does not.
TEST(CurvatureMeshSphere, ValenceFiveVerticesKeepTheirBarycentricBias) {
  constexpr double kRadius = 1.0;
  const TriangleMesh sphere = test::icosphere(kRadius, 4);
  const CurvatureResult angle = curvature(sphere, kAngle);
  const CurvatureResult cotangent = curvature(sphere, kCotangent);
  for (std::size_t v = 0; v < 12; ++v) {
    EXPECT_NEAR(angle.mean[v] * kRadius, 1.146, 2e-3) << "vertex " << v;
    EXPECT_NEAR(cotangent.mean[v] * kRadius, 1.0, 1e-4) << "vertex " << v;
  }
}

TEST(CurvatureMeshSphere, CotangentAgreesWithAngleBasedAwayFromValenceFive) {
  constexpr double kRadius = 1.0;
  const TriangleMesh sphere = test::icosphere(kRadius, 4);
  const CurvatureResult angle = curvature(sphere, kAngle);
  const CurvatureResult cotangent = curvature(sphere, kCotangent);
  std::vector<double> difference;
  for (std::size_t v = 12; v < sphere.vertices.size(); ++v) {  // 0..11: valence 5
    difference.push_back(std::abs(angle.mean[v] - cotangent.mean[v]) * kRadius);
  }
  std::printf("icosphere s=4 |H_angle - H_cot|*R: median %.2e, max %.2e\n",
              median(difference),
              quantile(difference, 1.0));
  EXPECT_LT(median(difference), 1e-3);
  EXPECT_LT(quantile(difference, 1.0), 5e-3);
}

// A latitude-longitude sphere has obtuse triangles towards the poles (Meyer's obtuse branch of
// the mixed area) and valence-4 vertices; the poles themselves have valence `slices`.
TEST(CurvatureMeshSphere, UvSphereWithObtuseTriangles) {
  constexpr double kRadius = 2.0;
  const TriangleMesh sphere = test::uvSphere(kRadius, 32, 64);
  const CurvatureResult angle = curvature(sphere, kAngle);
  const CurvatureResult cotangent = curvature(sphere, kCotangent);
  ASSERT_TRUE(angle.status.ok() && cotangent.status.ok());
  const std::vector<double> angle_error = errors(angle.mean, kRadius, 1.0);
  const std::vector<double> cotangent_error = errors(cotangent.mean, kRadius, 1.0);
  std::printf("uv sphere 32x64: median|HR-1| angle %.2e (max %.3f), cotangent %.2e (max %.2e)\n",
              median(angle_error),
              quantile(angle_error, 1.0),
              median(cotangent_error),
              quantile(cotangent_error, 1.0));
  EXPECT_LT(median(angle_error), 5e-3);
  EXPECT_LT(median(cotangent_error), 1e-3);
  EXPECT_LT(quantile(cotangent_error, 1.0), 2e-3);
  EXPECT_NEAR(sumOfProducts(angle.gaussian, angle.area), 4.0 * kPi, 1e-9);
}

// ----------------------------------------------------------------------- cylinder, saddle ---

TEST(CurvatureMeshCylinder, InteriorVerticesHaveHalfTheInverseRadius) {
  constexpr double kRadius = 0.5;
  const TriangleMesh tube = test::cylinderTube(kRadius, 1.0, 96, 32);
  const MeshAdjacency adjacency = buildMeshAdjacency(tube.faces, tube.vertices.size());
  for (const auto method : {kAngle, kCotangent}) {
    const CurvatureResult result = curvature(tube, method);
    ASSERT_TRUE(result.status.ok());
    double worst = 0.0;
    double worst_gaussian = 0.0;
    for (std::size_t v = 0; v < tube.vertices.size(); ++v) {
      if (!adjacency.boundary_vertex[v]) {
        worst = std::max(worst, std::abs(result.mean[v] * kRadius - 0.5));
        worst_gaussian = std::max(worst_gaussian, std::abs(result.gaussian[v]));
      }
    }
    std::printf("cylinder method %d: max|HR-0.5| %.2e, max|K| %.2e\n",
                static_cast<int>(method),
                worst,
                worst_gaussian);
    EXPECT_LT(worst, 3e-4) << "method " << static_cast<int>(method);
    EXPECT_LT(worst_gaussian, 1e-9);
    EXPECT_NEAR(sumOfProducts(result.gaussian, result.area), 0.0, 1e-9);  // χ(annulus) = 0
  }
}

TEST(CurvatureMeshSaddle, OriginHasZeroMeanAndNegativeGaussianCurvature) {
  constexpr double kA = 1.0;
  constexpr int kCells = 40;
  const TriangleMesh saddle = test::saddleGrid(kA, 0.4, kCells);
  const std::size_t origin = (kCells / 2) * (kCells + 1) + kCells / 2;
  ASSERT_NEAR(saddle.vertices[origin].norm(), 0.0, 1e-15);
  for (const auto method : {kAngle, kCotangent}) {
    const CurvatureResult result = curvature(saddle, method);
    ASSERT_TRUE(result.status.ok());
    std::printf("saddle method %d: H %.2e, K %.6f (exact 0, -1)\n",
                static_cast<int>(method),
                result.mean[origin],
                result.gaussian[origin]);
    EXPECT_LT(std::abs(result.mean[origin]) * kA, 1e-3);
    EXPECT_NEAR(result.gaussian[origin] * kA * kA, -1.0, 1e-2);
  }
}

// ---------------------------------------------------------------------------------- torus ---

// Torus p(u, v) = ((R + r cos v) cos u, (R + r cos v) sin u, r sin v), outward normal: the
// principal curvatures are 1/r (around the tube) and cos v / (R + r cos v) (around the axis),
// so H = (R + 2r cos v) / (2r (R + r cos v)): (R + 2r)/(2r(R + r)) on the outer equator (v = 0)
// and (R − 2r)/(2r(R − r)) on the inner one (v = π); K = cos v / (r (R + r cos v)).
double torusMean(double major, double minor, double v) {
  return (major + 2.0 * minor * std::cos(v)) / (2.0 * minor * (major + minor * std::cos(v)));
}

double torusGaussian(double major, double minor, double v) {
  return std::cos(v) / (minor * (major + minor * std::cos(v)));
}

TEST(CurvatureMeshTorus, EquatorsMatchTheAnalyticMeanCurvature) {
  constexpr double kMajor = 3.0;
  constexpr double kMinor = 1.0;
  constexpr int kAround = 192;
  constexpr int kTube = 64;
  const TriangleMesh ring = test::torus(kMajor, kMinor, kAround, kTube);
  for (const auto method : {kAngle, kCotangent}) {
    const CurvatureResult result = curvature(ring, method);
    ASSERT_TRUE(result.status.ok());
    double worst_outer = 0.0;
    double worst_inner = 0.0;
    for (int i = 0; i < kAround; ++i) {
      const auto outer = static_cast<std::size_t>(i * kTube);
      const auto inner = outer + kTube / 2;
      worst_outer = std::max(worst_outer,
                             std::abs(result.mean[outer] / torusMean(kMajor, kMinor, 0.0) - 1.0));
      worst_inner = std::max(worst_inner,
                             std::abs(result.mean[inner] / torusMean(kMajor, kMinor, kPi) - 1.0));
    }
    std::printf(
        "torus method %d: outer H exact %.4f max rel err %.2e, inner H exact %.4f max "
        "rel err %.2e\n",
        static_cast<int>(method),
        torusMean(kMajor, kMinor, 0.0),
        worst_outer,
        torusMean(kMajor, kMinor, kPi),
        worst_inner);
    EXPECT_LT(worst_outer, 3e-3) << "method " << static_cast<int>(method);
    EXPECT_LT(worst_inner, 3e-3) << "method " << static_cast<int>(method);
    EXPECT_NEAR(result.gaussian[0], torusGaussian(kMajor, kMinor, 0.0), 1e-2 * 0.25);
    EXPECT_NEAR(result.gaussian[kTube / 2], torusGaussian(kMajor, kMinor, kPi), 1e-2 * 0.5);
    EXPECT_NEAR(sumOfProducts(result.gaussian, result.area), 0.0, 1e-9);  // χ(torus) = 0
  }
}

TEST(CurvatureMeshOrientation, FlippingFacesFlipsMeanCurvatureAndNormals) {
  const TriangleMesh ring = test::torus(2.0, 0.7, 48, 24);
  const TriangleMesh inside_out = test::flipped(ring);
  for (const auto method : {kAngle, kCotangent}) {
    const CurvatureResult out = curvature(ring, method);
    const CurvatureResult in = curvature(inside_out, method);
    ASSERT_TRUE(out.status.ok() && in.status.ok());
    for (std::size_t v = 0; v < ring.vertices.size(); ++v) {
      ASSERT_NEAR(in.mean[v], -out.mean[v], 1e-12) << "vertex " << v;
      ASSERT_NEAR(in.gaussian[v], out.gaussian[v], 1e-12) << "vertex " << v;
      ASSERT_NEAR((in.normals[v] + out.normals[v]).norm(), 0.0, 1e-12) << "vertex " << v;
    }
  }
}

// ---------------------------------------------------------------------------------- noise ---

// Paper §4.1: one-ring curvature does not survive scanner noise. Relative spread = standard
// deviation of H·R over the vertices (the exact value is 1 everywhere).
TEST(CurvatureMeshNoise, OneRingMeanCurvatureIsRuinedByNoiseAlongNormals) {
  constexpr double kRadius = 1.0;
  constexpr unsigned kSeed = 31337;
  SCOPED_TRACE("noise seed " + std::to_string(kSeed));
  const TriangleMesh sphere = test::icosphere(kRadius, 4);
  const double clean = standardDeviation(curvature(sphere, kAngle).mean) * kRadius;
  std::vector<double> spread;
  for (const double fraction : {0.005, 0.02}) {
    const TriangleMesh noisy = test::addNormalNoise(sphere, fraction * 2.0 * kRadius, kSeed);
    const CurvatureResult result = curvature(noisy, kAngle);
    ASSERT_TRUE(result.status.ok());
    spread.push_back(standardDeviation(result.mean) * kRadius);
    std::printf(
        "icosphere s=4 noise %.1f %% of diameter: std(H*R) %.3f (clean %.4f), median "
        "H*R %.3f\n",
        100.0 * fraction,
        spread.back(),
        clean,
        median(result.mean) * kRadius);
  }
  EXPECT_LT(clean, 0.05);
  EXPECT_GT(spread[0], 1.0);  // 0.5 %: the spread is larger than H itself
  EXPECT_GT(spread[1], 3.0);  // 2 %: several times H; its sign is no longer reliable
}

// ------------------------------------------------------------------------- invalid input ---

TEST(CurvatureMeshInput, EmptyMeshIsDegenerate) {
  const CurvatureResult result = computeMeshCurvature({}, {}, MeshAdjacency{}, {});
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput);
  EXPECT_FALSE(result.status.message.empty());
}

TEST(CurvatureMeshInput, CollinearFacesAreDegenerate) {
  TriangleMesh line;
  line.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  line.faces = {{0, 1, 2}, {1, 2, 3}, {0, 0, 1}};
  const CurvatureResult result = curvature(line, kAngle);
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput);
  EXPECT_NE(result.status.message.find("non-zero area"), std::string::npos);
}

TEST(CurvatureMeshInput, FaceIndexOutOfRangeIsInvalid) {
  TriangleMesh sphere = test::icosphere(1.0, 1);
  const MeshAdjacency adjacency = buildMeshAdjacency(sphere.faces, sphere.vertices.size());
  for (const int bad : {42, -1, std::numeric_limits<int>::max()}) {
    TriangleMesh broken = sphere;
    broken.faces[7][1] = bad;
    const CurvatureResult result =
        computeMeshCurvature(broken.vertices, broken.faces, adjacency, {});
    EXPECT_EQ(result.status.code, StatusCode::kInvalidInput) << "index " << bad;
    EXPECT_NE(result.status.message.find("face 7"), std::string::npos) << result.status.message;
    EXPECT_TRUE(result.mean.empty());
  }
}

TEST(CurvatureMeshInput, NonFiniteVertexIsInvalid) {
  TriangleMesh sphere = test::icosphere(1.0, 1);
  sphere.vertices[3].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(curvature(sphere, kAngle).status.code, StatusCode::kInvalidInput);
}

TEST(CurvatureMeshInput, AdjacencyOfAnotherMeshIsInvalid) {
  const TriangleMesh small = test::icosphere(1.0, 1);
  const TriangleMesh large = test::icosphere(1.0, 2);
  const MeshAdjacency wrong = buildMeshAdjacency(large.faces, large.vertices.size());
  const CurvatureResult result = computeMeshCurvature(small.vertices, small.faces, wrong, {});
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_NE(result.status.message.find("adjacency"), std::string::npos);
}

TEST(CurvatureMeshInput, IsolatedVertexHasZeroCurvatureAndArea) {
  for (const auto method : {kAngle, kCotangent}) {
    TriangleMesh sphere = test::icosphere(1.0, 2);
    sphere.vertices.emplace_back(5.0, 5.0, 5.0);
    const CurvatureResult result = curvature(sphere, method);
    ASSERT_TRUE(result.status.ok()) << result.status.message;
    const std::size_t isolated = sphere.vertices.size() - 1;
    EXPECT_EQ(result.mean[isolated], 0.0);
    EXPECT_EQ(result.gaussian[isolated], 0.0);
    EXPECT_EQ(result.area[isolated], 0.0);
    EXPECT_EQ(result.normals[isolated], Eigen::Vector3d::Zero());
    EXPECT_NEAR(result.mean[0], 1.0, 0.2);
  }
}

}  // namespace
}  // namespace freeform_inspection
