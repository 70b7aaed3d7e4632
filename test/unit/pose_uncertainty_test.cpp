// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// The pose covariance against analytic values, its frames, and the spread of real ICP poses.
#include "freeform_inspection/pose_uncertainty.h"

#include <cmath>

#include "analytic_shapes.h"
#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/icp.h"
#include "freeform_inspection/mesh.h"
#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/synthetic_scan.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Points exactly on a surface: the deviation is zero and the normal is the surface's.
struct OnSurface {
  Points points;
  Points normals;
  std::vector<float> deviation;
};

// Points on a sphere with the cube's symmetries (every axis permutation and sign of a few
// Fibonacci points), so that Σ n nᵀ = N/3 · I exactly.
OnSurface sphere(double radius, const Eigen::Vector3d& centre, int base_count) {
  OnSurface s;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  const int permutations[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  for (int i = 0; i < base_count; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / base_count;
    const double r = std::sqrt(1.0 - z * z);
    const Eigen::Vector3d base(r * std::cos(golden * i), r * std::sin(golden * i), z);
    for (const auto& order : permutations) {
      for (int signs = 0; signs < 8; ++signs) {
        Eigen::Vector3d n;
        for (int a = 0; a < 3; ++a) {
          n[a] = ((signs >> a) & 1 ? -1.0 : 1.0) * base[order[a]];
        }
        s.points.push_back(centre + radius * n);
        s.normals.push_back(n);
        s.deviation.push_back(0.0F);
      }
    }
  }
  return s;
}

// A grid of points on each face of a box centred at `centre`, `per_side` along each edge.
OnSurface boxGrid(const Eigen::Vector3d& half, const Eigen::Vector3d& centre, int per_side) {
  OnSurface s;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    for (const double side : {-1.0, 1.0}) {
      for (int a = 0; a < per_side; ++a) {
        for (int b = 0; b < per_side; ++b) {
          Eigen::Vector3d p = Eigen::Vector3d::Zero();
          p[axis] = side * half[axis];
          p[u] = half[u] * (2.0 * (a + 0.5) / per_side - 1.0);
          p[v] = half[v] * (2.0 * (b + 0.5) / per_side - 1.0);
          Eigen::Vector3d n = Eigen::Vector3d::Zero();
          n[axis] = side;
          s.points.push_back(centre + p);
          s.normals.push_back(n);
          s.deviation.push_back(0.0F);
        }
      }
    }
  }
  return s;
}

TEST(PoseUncertainty, ASpheresShiftsAreKnownAndItsTurnsAreFree) {
  constexpr int kCount = 48 * 60;
  constexpr double kSigma = 1e-4;
  const OnSurface s = sphere(0.05, Eigen::Vector3d(0.2, -0.1, 0.3), kCount / 48);
  const PoseUncertainty u = estimatePoseUncertainty(
      s.points, s.normals, s.deviation, Eigen::Isometry3d::Identity(), 1e-3, kSigma, 0.17);
  ASSERT_TRUE(u.known);
  EXPECT_EQ(u.points, static_cast<std::size_t>(kCount));
  EXPECT_FALSE(u.constrained);
  // Σ n nᵀ = N/3 per axis, so each shift has σ √(3/N).
  EXPECT_NEAR(u.translation, kSigma * std::sqrt(3.0 / kCount), 1e-6 * u.translation);
  // A sphere turns freely about its centre: capped at a half turn.
  EXPECT_NEAR(u.rotation_deg, 180.0, 1e-6);
}

TEST(PoseUncertainty, ABoxOffTheOriginInATurnedScanFrame) {
  // A box centred d along the CAD x axis; the scan frame is the CAD frame turned 90° about z
  // (and shifted). Each shift is held by the faces across it, each turn by the faces' lever.
  const Eigen::Vector3d half(0.10, 0.06, 0.03);
  const double d = 0.5;
  const OnSurface s = boxGrid(half, Eigen::Vector3d(d, 0.0, 0.0), 20);
  constexpr double kSigma = 2e-4;
  Eigen::Isometry3d T_cad_scan = Eigen::Isometry3d::Identity();
  T_cad_scan.linear() = Eigen::AngleAxisd(kPi / 2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_cad_scan.translation() = Eigen::Vector3d(0.3, -0.2, 0.1);
  const PoseUncertainty u =
      estimatePoseUncertainty(s.points, s.normals, s.deviation, T_cad_scan, 1e-3, kSigma, 0.25);
  ASSERT_TRUE(u.known);
  EXPECT_TRUE(u.constrained);

  // Points per face pair across each axis, and the turn about z's information about the box's
  // centre: the ±x faces' y², the ±y faces' (x − d)².
  const double per_pair = 2.0 * 20 * 20;
  double turn_z = 0.0;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const Eigen::Vector3d local = s.points[i] - Eigen::Vector3d(d, 0.0, 0.0);
    if (std::abs(s.normals[i].x()) > 0.5) {
      turn_z += local.y() * local.y();
    } else if (std::abs(s.normals[i].y()) > 0.5) {
      turn_z += local.x() * local.x();
    }
  }
  const double var_shift = kSigma * kSigma / per_pair;
  const double var_turn_z = kSigma * kSigma / turn_z;
  const auto& c = u.covariance;
  // The scan frame's x is the CAD's y: the CAD origin, d from the box, swings with the turn
  // about z along CAD y, that is along scan x.
  EXPECT_NEAR(c(0, 0), var_shift + d * d * var_turn_z, 1e-9 * c(0, 0) + 1e-18);
  EXPECT_NEAR(c(1, 1), var_shift, 1e-6 * var_shift);
  EXPECT_NEAR(c(5, 5), var_turn_z, 1e-6 * var_turn_z);
  // The swing and the turn are one motion: fully correlated up to the shift's own share.
  EXPECT_NEAR(
      c(0, 5) * c(0, 5), d * d * var_turn_z * var_turn_z, 1e-6 * d * d * var_turn_z * var_turn_z);
  EXPECT_NEAR(c(1, 5), 0.0, 1e-12);
  // Symmetric, and the same spread whatever the frame for the centroid's shift and the turn.
  EXPECT_LT((c - c.transpose()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_NEAR(u.translation, std::sqrt(var_shift), 1e-6 * std::sqrt(var_shift));
  // Read back at the box's centre (scan frame) the turns' lever is gone: three shifts alone.
  const Eigen::Vector3d centre_scan = T_cad_scan.inverse() * Eigen::Vector3d(d, 0.0, 0.0);
  const PredictedSpread at_centre = predictedSpread(u, T_cad_scan, centre_scan);
  EXPECT_NEAR(at_centre.at_point * at_centre.at_point, 3.0 * var_shift, 1e-6 * var_shift);
  const double turn_trace = c(3, 3) + c(4, 4) + c(5, 5);
  EXPECT_NEAR(at_centre.rotation * at_centre.rotation, turn_trace, 1e-12 * turn_trace);
}

TEST(PoseUncertainty, LeavesOutPointsBeyondTheInlierDistance) {
  OnSurface s = sphere(0.05, Eigen::Vector3d::Zero(), 12);  // 576 points
  for (std::size_t i = 0; i < s.points.size(); i += 3) {
    s.deviation[i] = 0.01F;  // a defect or outlier, 10 mm off
  }
  s.deviation[1] = std::numeric_limits<float>::quiet_NaN();  // unmatched
  s.normals[2] = Eigen::Vector3d::Zero();
  const PoseUncertainty u = estimatePoseUncertainty(
      s.points, s.normals, s.deviation, Eigen::Isometry3d::Identity(), 1e-3, 1e-4, 0.1);
  ASSERT_TRUE(u.known);
  EXPECT_EQ(u.points, 576u - 192u - 2u);
}

TEST(PoseUncertainty, UnknownWithoutEnoughPointsOrANoiseEstimate) {
  OnSurface s = sphere(0.05, Eigen::Vector3d::Zero(), 1);
  s.points.resize(5);
  s.normals.resize(5);
  s.deviation.resize(5);
  EXPECT_FALSE(estimatePoseUncertainty(
                   s.points, s.normals, s.deviation, Eigen::Isometry3d::Identity(), 1e-3, 1e-4, 0.1)
                   .known);
  const OnSurface many = sphere(0.05, Eigen::Vector3d::Zero(), 2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(
      estimatePoseUncertainty(
          many.points, many.normals, many.deviation, Eigen::Isometry3d::Identity(), 1e-3, nan, 0.1)
          .known);
  EXPECT_FALSE(
      estimatePoseUncertainty(
          many.points, many.normals, many.deviation, Eigen::Isometry3d::Identity(), 0.0, 1e-4, 0.1)
          .known);
  // Exact data: known, and nothing moves.
  const OnSurface box = boxGrid(Eigen::Vector3d(0.1, 0.06, 0.03), Eigen::Vector3d::Zero(), 5);
  const PoseUncertainty exact = estimatePoseUncertainty(
      box.points, box.normals, box.deviation, Eigen::Isometry3d::Identity(), 1e-3, 0.0, 0.25);
  ASSERT_TRUE(exact.known);
  EXPECT_TRUE(exact.constrained);
  EXPECT_EQ(exact.covariance.cwiseAbs().maxCoeff(), 0.0);
}

// The covariance describes real ICP poses: noisy scans of a box at a random pose, refined from
// the truth; on planes point-to-plane ICP is linear, so the spread of its poses is the
// covariance's (within the sampling error of 24 poses).
TEST(PoseUncertainty, PredictsTheSpreadOfIcpPosesOnABox) {
  const TriangleMesh box = test::makeBox(Eigen::Vector3d(0.10, 0.06, 0.03));
  const MeshQuery cad(box);
  const double diagonal = computeBoundingBox(box.vertices).diagonal();
  constexpr int kScans = 24;
  double rotation_sq = 0.0, predicted_rotation_sq = 0.0;
  double shift_sq = 0.0, predicted_shift_sq = 0.0;
  for (int k = 0; k < kScans; ++k) {
    SyntheticScanConfig config;
    config.points = 4000;
    config.noise_ratio = 0.002;
    config.seed = 100 + static_cast<std::uint64_t>(k);
    const SyntheticScan generated = makeSyntheticScan(cad, config);
    ASSERT_TRUE(generated.status.ok());
    IcpConfig icp_config;
    const IcpResult icp = refinePose(cad,
                                     generated.scan.points,
                                     generated.T_cad_scan,
                                     3.0 * config.noise_ratio * diagonal,
                                     diagonal,
                                     icp_config);
    ASSERT_TRUE(icp.usable());
    Points points_cad;
    Points normals;
    std::vector<float> deviation;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : generated.scan.points) {
      const ClosestPoint closest = cad.closest(icp.T_cad_scan * p, 0.05 * diagonal);
      points_cad.push_back(icp.T_cad_scan * p);
      normals.push_back(closest.found ? closest.normal : Eigen::Vector3d::Zero());
      deviation.push_back(closest.found ? static_cast<float>(closest.signed_distance)
                                        : std::numeric_limits<float>::quiet_NaN());
      centroid += p / static_cast<double>(generated.scan.points.size());
    }
    const PoseUncertainty u = estimatePoseUncertainty(
        points_cad, normals, deviation, icp.T_cad_scan, icp.inlier_distance, icp.sigma, diagonal);
    ASSERT_TRUE(u.known);
    ASSERT_TRUE(u.constrained);
    // The errors of the turn and of the scan's centroid, and what the covariance (part pose in
    // the scan frame, as a ROS user reads it) predicts for them.
    const Eigen::AngleAxisd turn(icp.T_cad_scan.linear().transpose() *
                                 generated.T_cad_scan.linear());
    rotation_sq += turn.angle() * turn.angle();
    shift_sq += (icp.T_cad_scan * centroid - generated.T_cad_scan * centroid).squaredNorm();
    const PredictedSpread predicted = predictedSpread(u, icp.T_cad_scan, centroid);
    predicted_rotation_sq += predicted.rotation * predicted.rotation;
    predicted_shift_sq += predicted.at_point * predicted.at_point;
  }
  const double rotation_ratio = std::sqrt(rotation_sq / predicted_rotation_sq);
  const double shift_ratio = std::sqrt(shift_sq / predicted_shift_sq);
  EXPECT_GT(rotation_ratio, 0.7);
  EXPECT_LT(rotation_ratio, 1.4);
  EXPECT_GT(shift_ratio, 0.7);
  EXPECT_LT(shift_ratio, 1.4);
}

}  // namespace
}  // namespace freeform_inspection
