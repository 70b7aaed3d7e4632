// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// ICP (paper §3.6.2, eq. 15) against exact CAD triangles, from known perturbations.
#include "freeform_inspection/icp.h"

#include <cmath>
#include <cstdio>
#include <random>

#include "analytic_shapes.h"
#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh.h"
#include "freeform_inspection/surface_sampling.h"

namespace freeform_inspection {
namespace {

constexpr unsigned kSeed = 21;

// The shipped blade: no symmetry, so every motion changes the distances (a torus or a sphere
// would let ICP slide about its axis).
TriangleMesh part() {
  static const TriangleMesh mesh =
      loadMesh(std::string(FREEFORM_DATA_DIR) + "/blade/blade.stl", 0.001).mesh;
  return mesh;
}

double diagonalOf(const TriangleMesh& mesh) {
  return computeBoundingBox(mesh.vertices).diagonal();
}

Eigen::Isometry3d perturbation(double angle_deg,
                               const Eigen::Vector3d& axis,
                               const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(angle_deg * M_PI / 180.0, axis.normalized()).toRotationMatrix();
  T.translation() = t;
  return T;
}

double angleDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}

// Scan points in a frame moved by `T_scan_cad`; ICP must find its inverse.
Points moved(const Points& points, const Eigen::Isometry3d& T_scan_cad) {
  Points out;
  for (const auto& p : points) {
    out.push_back(T_scan_cad * p);
  }
  return out;
}

TEST(Icp, PointToPlaneRecoversAPerturbationExactly) {
  const TriangleMesh mesh = part();
  const MeshQuery cad(mesh);
  const Eigen::Isometry3d T_scan_cad =
      perturbation(4.0, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.003, -0.002, 0.001));
  const Points scan = moved(sampleSurface(mesh, 5000, kSeed).points, T_scan_cad);
  const double diagonal = diagonalOf(mesh);
  const IcpResult result =
      refinePose(cad, scan, Eigen::Isometry3d::Identity(), 0.02, diagonal, IcpConfig());
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_TRUE(result.converged);
  EXPECT_LT(angleDeg(result.T_cad_scan, T_scan_cad.inverse()), 1e-4);
  EXPECT_LT((result.T_cad_scan.translation() - T_scan_cad.inverse().translation()).norm(), 1e-6);
  EXPECT_GT(result.fitness, 0.999);
  EXPECT_LT(result.rmse, 1e-6);
}

TEST(Icp, PaperPointToPointAlsoConvergesButNeedsMoreIterations) {
  const TriangleMesh mesh = part();
  const MeshQuery cad(mesh);
  const Eigen::Isometry3d T_scan_cad =
      perturbation(4.0, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.003, -0.002, 0.001));
  // With a little noise the mean squared error settles and eq. 15 can stop it (on exact data
  // point-to-point converges only linearly and the relative criterion keeps it going).
  const Points scan = moved(sampleSurface(mesh, 5000, kSeed, 0.0001).points, T_scan_cad);
  IcpConfig plane;
  IcpConfig point;
  point.point_to_plane = false;
  point.max_iterations = 500;
  point.convergence = 1e-6;
  const IcpResult by_plane =
      refinePose(cad, scan, Eigen::Isometry3d::Identity(), 0.02, diagonalOf(mesh), plane);
  const IcpResult by_point =
      refinePose(cad, scan, Eigen::Isometry3d::Identity(), 0.02, diagonalOf(mesh), point);
  ASSERT_TRUE(by_point.status.ok()) << by_point.status.message << ", "
                                    << angleDeg(by_point.T_cad_scan, T_scan_cad.inverse()) << "°";
  EXPECT_LT(angleDeg(by_point.T_cad_scan, T_scan_cad.inverse()), 0.05);
  EXPECT_GT(by_point.iterations, by_plane.iterations);
}

TEST(Icp, NoiseDoesNotBiasThePoseAndIsMeasured) {
  const TriangleMesh mesh = part();
  const MeshQuery cad(mesh);
  const double sigma = 0.0002;  // 0.2 mm along the normals
  const Eigen::Isometry3d T_scan_cad =
      perturbation(3.0, Eigen::Vector3d(-1, 0.5, 2), Eigen::Vector3d(-0.002, 0.001, 0.002));
  const Points scan = moved(sampleSurface(mesh, 20000, kSeed, sigma).points, T_scan_cad);
  const IcpResult result =
      refinePose(cad, scan, Eigen::Isometry3d::Identity(), 0.02, diagonalOf(mesh), IcpConfig());
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_LT(angleDeg(result.T_cad_scan, T_scan_cad.inverse()), 0.05);
  EXPECT_LT((result.T_cad_scan.translation() - T_scan_cad.inverse().translation()).norm(),
            0.1 * sigma);
  EXPECT_NEAR(result.sigma, sigma, 0.05 * sigma);
  // Inliers within 3σ of a Gaussian: 99.7 % of the points, RMS 0.986 σ.
  EXPECT_NEAR(result.fitness, 0.997, 0.003);
  EXPECT_NEAR(result.rmse, 0.986 * sigma, 0.03 * sigma);
}

// On a noisy scan the pairs trade faces between iterations and the mean squared error jitters
// by about 1e-4 of itself, so eq. 15 alone (1e-5) runs on. The steps then move no point by a
// hundredth of the noise, and stopping there leaves the pose within a hundredth of a degree and
// of the noise of where eq. 15 stops (the pose's own statistical error, σ/√n, is 0.007 σ).
TEST(Icp, NoisyScanStopsOnceNoStepMovesAPointByAHundredthOfTheNoise) {
  // A cast link of 5,097 triangles: flat faces meeting at edges, where noisy points change face.
  const TriangleMesh mesh =
      loadMesh(std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/kuka_kr10r900_2_link_4.stl", 1.0)
          .mesh;
  const MeshQuery cad(mesh);
  const double diagonal = diagonalOf(mesh);
  const double sigma = 0.005 * diagonal;
  IcpConfig eq15_only;
  eq15_only.still_fraction = 0.0;
  // From 3° the pose is reached in a few steps; from 15° the residual is wide at first and the
  // steps small against it while they still lead somewhere: the rule must not stop there.
  for (const double start_deg : {3.0, 15.0}) {
    const Eigen::Isometry3d T_scan_cad =
        perturbation(start_deg, Eigen::Vector3d(2, -1, 1), Eigen::Vector3d(0.001, 0.002, -0.001));
    const Points scan = moved(sampleSurface(mesh, 20000, kSeed, sigma).points, T_scan_cad);
    const IcpResult stopped =
        refinePose(cad, scan, Eigen::Isometry3d::Identity(), 0.05, diagonal, IcpConfig());
    const IcpResult full =
        refinePose(cad, scan, Eigen::Isometry3d::Identity(), 0.05, diagonal, eq15_only);
    ASSERT_TRUE(stopped.status.ok()) << stopped.status.message;
    ASSERT_TRUE(full.usable()) << full.status.message;
    std::printf(
        "from %.0f°: %d iterations with the step rule, %d with eq. 15 alone, %.4f° and "
        "%.4f σ apart\n",
        start_deg,
        stopped.iterations,
        full.iterations,
        angleDeg(stopped.T_cad_scan, full.T_cad_scan),
        (stopped.T_cad_scan.translation() - full.T_cad_scan.translation()).norm() / sigma);
    EXPECT_LT(stopped.iterations, full.iterations) << start_deg;
    EXPECT_LT(angleDeg(stopped.T_cad_scan, full.T_cad_scan), 0.01) << start_deg;
    EXPECT_LT((stopped.T_cad_scan.translation() - full.T_cad_scan.translation()).norm(),
              0.01 * sigma)
        << start_deg;
    EXPECT_LT(angleDeg(stopped.T_cad_scan, T_scan_cad.inverse()), 0.1) << start_deg;
  }
}

// measureFit is refinePose's own final fit, at a pose it does not move: the same numbers at
// the refined pose, and a worse fit at a pose shifted away from it.
TEST(Icp, MeasureFitIsTheFitAtAGivenPose) {
  const TriangleMesh mesh = part();
  const MeshQuery cad(mesh);
  const double sigma = 0.0002;
  const Eigen::Isometry3d T_scan_cad =
      perturbation(2.0, Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(0.001, 0.0, -0.001));
  const Points scan = moved(sampleSurface(mesh, 20000, kSeed, sigma).points, T_scan_cad);
  const IcpResult refined =
      refinePose(cad, scan, Eigen::Isometry3d::Identity(), 0.02, diagonalOf(mesh), IcpConfig());
  ASSERT_TRUE(refined.status.ok()) << refined.status.message;
  const IcpResult at_pose =
      measureFit(cad, scan, refined.T_cad_scan, diagonalOf(mesh), IcpConfig());
  EXPECT_TRUE(at_pose.T_cad_scan.isApprox(refined.T_cad_scan, 0.0));
  EXPECT_EQ(at_pose.iterations, 0);
  EXPECT_DOUBLE_EQ(at_pose.sigma, refined.sigma);
  EXPECT_DOUBLE_EQ(at_pose.inlier_distance, refined.inlier_distance);
  EXPECT_DOUBLE_EQ(at_pose.rmse, refined.rmse);
  EXPECT_DOUBLE_EQ(at_pose.fitness, refined.fitness);
  const Eigen::Isometry3d shifted =
      perturbation(0.0, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0.002, 0.0, 0.0)) *
      refined.T_cad_scan;  // 2 mm = 10 σ
  const IcpResult off = measureFit(cad, scan, shifted, diagonalOf(mesh), IcpConfig());
  EXPECT_GT(off.sigma, 2.0 * refined.sigma);
  EXPECT_LT(off.fitness, refined.fitness);
}

TEST(Icp, TrimmingIgnoresOutliersAndAPartThatIsNotInTheCad) {
  const TriangleMesh mesh = part();
  const MeshQuery cad(mesh);
  const Eigen::Isometry3d T_scan_cad =
      perturbation(3.0, Eigen::Vector3d(0, 1, 1), Eigen::Vector3d(0.002, 0.002, -0.001));
  Points points = sampleSurface(mesh, 8000, kSeed).points;
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> box(-0.15, 0.15);
  for (int i = 0; i < 2000; ++i) {  // 20 % clutter around the part
    points.emplace_back(box(rng), box(rng), box(rng));
  }
  const BoundingBox bounds = computeBoundingBox(mesh.vertices);
  for (int i = 0; i < 1000; ++i) {  // a fixture plate 5 mm under the part
    points.emplace_back(box(rng), box(rng), bounds.min.z() - 0.005);
  }
  const IcpResult result = refinePose(cad,
                                      moved(points, T_scan_cad),
                                      Eigen::Isometry3d::Identity(),
                                      0.02,
                                      diagonalOf(mesh),
                                      IcpConfig());
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_LT(angleDeg(result.T_cad_scan, T_scan_cad.inverse()), 0.01);
  EXPECT_LT((result.T_cad_scan.translation() - T_scan_cad.inverse().translation()).norm(), 1e-5);
  EXPECT_NEAR(result.fitness, 8000.0 / 11000.0, 0.03);
}

TEST(Icp, ScanFarFromTheCadIsALostSurfaceNotAPose) {
  const TriangleMesh mesh = part();
  const MeshQuery cad(mesh);
  const Points scan =
      moved(sampleSurface(mesh, 500, kSeed).points,
            perturbation(0.0, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(5.0, 0, 0)));
  const IcpResult result =
      refinePose(cad, scan, Eigen::Isometry3d::Identity(), 0.02, diagonalOf(mesh), IcpConfig());
  EXPECT_EQ(result.status.code, StatusCode::kRegistrationFailed);
  EXPECT_NE(result.status.message.find("lost the surface"), std::string::npos);
}

// How far `points` moved by `motion` end up from the surface of `cad`, at most.
double farthestOffSurface(const MeshQuery& cad,
                          const Points& points,
                          const Eigen::Isometry3d& motion) {
  double farthest = 0.0;
  for (const auto& p : points) {
    farthest = std::max(farthest, cad.closest(motion * p).distance);
  }
  return farthest;
}

// A tube's points slide along its axis and turn about it without leaving the surface: the two
// motions a fit cannot see (zero stiffness but for the facets), which a view of a prismatic part
// slides along. Every other motion takes the points off it.
TEST(Icp, WeakestMotionsOfATubeAreAlongAndAboutItsAxis) {
  const TriangleMesh tube = test::cylinderTube(0.05, 0.3, 96, 40);
  const MeshQuery cad(tube);
  const Points points = sampleSurface(tube, 3000, kSeed).points;
  const std::vector<WeakMotion> motions =
      weakestMotions(cad, points, Eigen::Isometry3d::Identity(), 0.01, 6);
  ASSERT_EQ(motions.size(), 6u);
  for (std::size_t k = 0; k + 1 < motions.size(); ++k) {
    EXPECT_LE(motions[k].stiffness, motions[k + 1].stiffness);
  }
  // The facets leave a stiffness of (facet width / √12 / radius)² ≈ 1e-4 to the turn.
  EXPECT_LT(motions[0].stiffness, 1e-3);
  EXPECT_LT(motions[1].stiffness, 1e-3);
  EXPECT_GT(motions[2].stiffness, 0.05);
  // One slides along z, the other turns about it (through the points' centroid, which the
  // random sample puts a millimetre off the axis, so with a small shift).
  const Eigen::Vector3d z(0.0, 0.0, 1.0);
  const bool slide_first = motions[0].rotation.norm() < motions[1].rotation.norm();
  const WeakMotion& slide = motions[slide_first ? 0 : 1];
  const WeakMotion& turn = motions[slide_first ? 1 : 0];
  EXPECT_GT(std::abs(slide.translation.normalized().dot(z)), 0.999);
  EXPECT_LT(slide.rotation.norm(), 1e-3);
  EXPECT_GT(std::abs(turn.rotation.normalized().dot(z)), 0.999);
  // 1 cm of either keeps the points of the tube's middle (away from its open ends) within
  // 0.1 mm (the facets' sagitta) of it; 1 cm of the next motion takes some millimetres off.
  Points middle;
  for (const auto& p : points) {
    if (std::abs(p.z()) < 0.1) {
      middle.push_back(p);
    }
  }
  EXPECT_LT(farthestOffSurface(cad, middle, slide.by(0.01)), 1e-4);
  EXPECT_LT(farthestOffSurface(cad, middle, turn.by(0.01)), 1e-4);
  EXPECT_GT(farthestOffSurface(cad, middle, motions[2].by(0.01)), 2e-3);
}

TEST(Icp, EveryMotionOfABoxIsStiff) {
  const TriangleMesh box = test::makeBox(Eigen::Vector3d(0.05, 0.03, 0.02));
  const MeshQuery cad(box);
  const Points points = sampleSurface(box, 3000, kSeed).points;
  const std::vector<WeakMotion> motions =
      weakestMotions(cad, points, Eigen::Isometry3d::Identity(), 0.01, 2);
  ASSERT_EQ(motions.size(), 2u);
  EXPECT_GT(motions[0].stiffness, 0.02);
  // Too few points near the CAD: no motions to tell.
  EXPECT_TRUE(
      weakestMotions(cad, {Eigen::Vector3d(1.0, 1.0, 1.0)}, Eigen::Isometry3d::Identity(), 0.01, 2)
          .empty());
}

// A noisy view of a 2 mm sheet (σ = 1.2 mm along the normals, the bent bracket of test/data):
// a point pushed more than 1 mm into the sheet is nearer its far side, and pairs made there pull
// the pose into the sheet. Paired only with the faces turned its way, the fit stays where the
// surface is.
TEST(Icp, PairsWithTheFacesTurnedTheirWayOnAWallThinnerThanTheNoise) {
  const TriangleMesh sheet =
      loadMesh(std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/bent_sheet_bracket.stl", 1.0).mesh;
  const MeshQuery cad(sheet);
  ASSERT_TRUE(cad.status().ok());
  const double sigma = 0.0012;
  const SurfaceSample all = sampleSurface(sheet, 40000, kSeed, sigma);
  // The outer side of both legs and the bend (outward normals +z on the long leg, −x on the
  // short one): what a sensor on the outside sees.
  const Eigen::Vector3d outside = Eigen::Vector3d(-1.0, 0.0, 1.0).normalized();
  Points points;
  Points normals;
  for (std::size_t i = 0; i < all.points.size(); ++i) {
    if (all.normals[i].dot(outside) > 0.5) {
      points.push_back(all.points[i]);
      normals.push_back(all.normals[i]);
    }
  }
  ASSERT_GT(points.size(), 10000u);
  const double diagonal = diagonalOf(sheet);
  const Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  const IcpResult nearest = refinePose(cad, points, truth, 3 * sigma, diagonal, IcpConfig());
  const IcpResult facing =
      refinePose(cad, points, truth, 3 * sigma, diagonal, IcpConfig(), normals);
  ASSERT_TRUE(nearest.usable() && facing.usable());
  // Off the sheet: the shift in the plane of its profile (x, z). Along its width (y) only the
  // bead holds the view, and there the noise of 10,000 points leaves a few tenths of a millimetre.
  const auto across = [](const IcpResult& fit) {
    return Eigen::Vector2d(fit.T_cad_scan.translation().x(), fit.T_cad_scan.translation().z())
        .norm();
  };
  std::printf("shift off the sheet: nearest face %.3f mm, facing face %.3f mm\n",
              1e3 * across(nearest),
              1e3 * across(facing));
  EXPECT_GT(across(nearest), 0.2 * sigma);
  EXPECT_LT(across(facing), 0.1 * sigma);
  EXPECT_LT(angleDeg(facing.T_cad_scan, truth), 0.05);
  // The measured noise is the noise itself once no pair crosses the sheet.
  EXPECT_NEAR(facing.sigma, sigma, 0.05 * sigma);
  EXPECT_LT(nearest.sigma, 0.9 * sigma);
  // 180° compares nothing: the nearest face again.
  IcpConfig off;
  off.facing_tolerance_deg = 180.0;
  const IcpResult unfiltered = refinePose(cad, points, truth, 3 * sigma, diagonal, off, normals);
  EXPECT_EQ(unfiltered.T_cad_scan.matrix(), nearest.T_cad_scan.matrix());
}

// Half a tube of radius 20 mm cut into 12 flat strips (a CAD exported with 15° facets) and
// points on the round half tube it stands for, each strip's arc 0.17 mm outside it at its
// middle (chord_error.h). From the true pose, ICP on the faces moves the points into them along
// the half's axis of symmetry; ICP that fits the curve's share with the pose finds the whole
// curve (share 1) and stays. Points on the strips themselves find share 0.
TEST(Icp, CoarseHalfTubeFitsTheCurveItsStripsStandFor) {
  const double radius = 0.02;
  const int strips = 12;
  TriangleMesh cad;
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; j <= strips; ++j) {
      const double phi = M_PI * j / strips;
      cad.vertices.emplace_back(radius * std::cos(phi), radius * std::sin(phi), 0.01 * i - 0.02);
    }
  }
  cad.faces = test::latticeFaces(4, strips + 1, false);
  cad.face_normals = computeFaceNormals(cad.vertices, cad.faces);
  if (cad.face_normals.front().y() < 0.0) {  // outward, away from the axis
    for (Eigen::Vector3i& face : cad.faces) {
      std::swap(face[1], face[2]);
    }
    cad.face_normals = computeFaceNormals(cad.vertices, cad.faces);
  }
  const MeshQuery query(cad);
  const ChordError chord = estimateChordError(cad);
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> around(0.02, M_PI - 0.02);
  std::uniform_real_distribution<double> along(-0.018, 0.018);
  std::normal_distribution<double> noise(0.0, 2e-5);  // 0.02 mm along the normal
  Points round;
  Points flat;
  for (int k = 0; k < 4000; ++k) {
    const double phi = around(rng);
    const Eigen::Vector3d normal(std::cos(phi), std::sin(phi), 0.0);
    const Eigen::Vector3d on_arc = radius * normal + Eigen::Vector3d(0.0, 0.0, along(rng));
    round.push_back(on_arc + noise(rng) * normal);
    // The point of the strip below it, as a scan made from the mesh would have it.
    const ClosestPoint on_strip = query.closest(on_arc, 0.01);
    flat.push_back(on_strip.point + noise(rng) * on_strip.normal);
  }
  const double diagonal = computeBoundingBox(cad.vertices).diagonal();
  IcpConfig config;
  const Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  const IcpResult faces = refinePose(query, round, truth, 0.002, diagonal, config);
  ASSERT_TRUE(faces.usable());
  EXPECT_GT(faces.T_cad_scan.translation().head<2>().norm(), 1e-4);  // 0.1 mm into the strips

  CurvedSurface curved;
  curved.chord = &chord;
  curved.estimate = true;
  const IcpResult curve = refinePose(query, round, truth, 0.002, diagonal, config, {}, curved);
  ASSERT_TRUE(curve.usable());
  // The strips at the half's two edges have no neighbour beyond: their bulge reads half, and the
  // share comes out a little over 1. The fit does not hold the turn about the axis or the slide
  // along it: the pose is judged on its other four motions.
  EXPECT_NEAR(curve.curve_share, 1.0, 0.15);
  EXPECT_LT(curve.curve_share_error, 0.02);
  const auto across = [](const Eigen::Isometry3d& T) { return T.translation().head<2>().norm(); };
  EXPECT_LT(across(curve.T_cad_scan), 0.25 * across(faces.T_cad_scan));  // 0.023 against 0.146 mm
  const double tilt =
      std::acos(std::min(1.0, (curve.T_cad_scan.linear() * Eigen::Vector3d::UnitZ()).z()));
  EXPECT_LT(tilt * 180.0 / M_PI, 0.05);

  const IcpResult on_strips = refinePose(query, flat, truth, 0.002, diagonal, config, {}, curved);
  ASSERT_TRUE(on_strips.usable());
  EXPECT_NEAR(on_strips.curve_share, 0.0, 0.02);
  EXPECT_LT(on_strips.T_cad_scan.translation().head<2>().norm(), 2e-6);
  // Read without moving the pose: all of the curve at the true pose, none on the strips.
  EXPECT_NEAR(curveShareAt(query, chord, round, truth, 0.001, config).share, 1.0, 0.1);
  EXPECT_NEAR(curveShareAt(query, chord, flat, truth, 0.001, config).share, 0.0, 0.02);
}

TEST(IcpConfig, ValidationNamesTheField) {
  IcpConfig config;
  EXPECT_TRUE(validate(config).empty());
  config.max_iterations = 0;
  config.min_cutoff_ratio = 1.0;
  config.still_fraction = -0.1;
  config.facing_tolerance_deg = 0.0;
  const auto errors = validate(config);
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_NE(errors[0].find("icp.max_iterations"), std::string::npos);
  EXPECT_NE(errors[1].find("icp.still_fraction"), std::string::npos);
  EXPECT_NE(errors[2].find("icp.min_cutoff_ratio"), std::string::npos);
  EXPECT_NE(errors[3].find("icp.facing_tolerance_deg"), std::string::npos);
}

}  // namespace
}  // namespace freeform_inspection
