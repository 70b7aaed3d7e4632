// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/pose_uncertainty.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace freeform_inspection {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

constexpr double kPi = 3.14159265358979323846;
// An eigenvalue of the information this far below the largest is a motion the data do not hold
// (rounding, not geometry).
constexpr double kFreeRatio = 1e-12;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

double largestStd(const Eigen::Matrix3d& covariance) {
  const double largest =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance, Eigen::EigenvaluesOnly)
          .eigenvalues()
          .maxCoeff();
  return std::sqrt(std::max(0.0, largest));
}

}  // namespace

PoseUncertainty estimatePoseUncertainty(const Points& points_cad,
                                        const Points& cad_normals,
                                        const std::vector<float>& deviation,
                                        const Eigen::Isometry3d& T_cad_scan,
                                        double inlier_distance,
                                        double sigma,
                                        double cad_diagonal) {
  PoseUncertainty out;
  const std::size_t n = std::min({points_cad.size(), cad_normals.size(), deviation.size()});
  if (!(sigma >= 0.0 && std::isfinite(sigma)) || !(inlier_distance > 0.0) ||
      !(cad_diagonal > 0.0 && std::isfinite(cad_diagonal))) {
    return out;
  }
  std::vector<std::size_t> inliers;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const double d = deviation[i];
    if (std::isfinite(d) && std::abs(d) <= inlier_distance && points_cad[i].allFinite() &&
        cad_normals[i].squaredNorm() > 0.5) {
      inliers.push_back(i);
      centroid += points_cad[i];
    }
  }
  if (inliers.size() < 6) {
    return out;
  }
  centroid /= static_cast<double>(inliers.size());

  // Information of the point-to-plane residuals for a turn ω about the centroid and a shift u
  // in CAD diagonals (so that both are compared on the part's scale), CAD frame.
  Matrix6 information = Matrix6::Zero();
  for (const std::size_t i : inliers) {
    Vector6 row;
    row << (points_cad[i] - centroid).cross(cad_normals[i]), cad_diagonal * cad_normals[i];
    information.selfadjointView<Eigen::Lower>().rankUpdate(row);
  }
  information = information.selfadjointView<Eigen::Lower>();

  // σ² H⁻¹ through the eigenvectors, each variance capped at π²: a half turn, or π diagonals.
  const Eigen::SelfAdjointEigenSolver<Matrix6> solver(information);
  const double largest = solver.eigenvalues().maxCoeff();
  const double cap = kPi * kPi;
  Vector6 variance;
  out.constrained = largest > 0.0;
  for (int k = 0; k < 6; ++k) {
    const double lambda = solver.eigenvalues()(k);
    const bool held = lambda > kFreeRatio * largest && sigma * sigma < cap * lambda;
    variance(k) = held ? sigma * sigma / lambda : cap;
    out.constrained = out.constrained && held;
  }
  Matrix6 scaled =
      solver.eigenvectors() * variance.asDiagonal() * solver.eigenvectors().transpose();

  // Back to metres, then from the centroid to the CAD origin: v = v_c + c × ω.
  Matrix6 metres = Matrix6::Identity();
  metres.bottomRightCorner<3, 3>() *= cad_diagonal;
  const Matrix6 about_centroid = metres * scaled * metres;
  Matrix6 to_origin = Matrix6::Identity();
  to_origin.bottomLeftCorner<3, 3>() = skew(centroid);
  const Matrix6 about_origin = to_origin * about_centroid * to_origin.transpose();

  // T_cad_scan moved by (ω, v) in the CAD frame moves its inverse, the part in the scan frame,
  // by −R v at the part's origin and −R ω about the scan frame's axes (R: CAD → scan).
  const Eigen::Matrix3d R = T_cad_scan.linear().transpose();
  Matrix6 to_ros = Matrix6::Zero();
  to_ros.topRightCorner<3, 3>() = -R;
  to_ros.bottomLeftCorner<3, 3>() = -R;
  const Matrix6 covariance = to_ros * about_origin * to_ros.transpose();
  out.covariance = 0.5 * (covariance + covariance.transpose());  // exactly symmetric

  out.rotation_deg = largestStd(about_centroid.topLeftCorner<3, 3>()) * 180.0 / kPi;
  out.translation = largestStd(about_centroid.bottomRightCorner<3, 3>());
  out.points = inliers.size();
  out.known = true;
  return out;
}

PredictedSpread predictedSpread(const PoseUncertainty& uncertainty,
                                const Eigen::Isometry3d& T_cad_scan,
                                const Eigen::Vector3d& point_scan) {
  const Matrix6& c = uncertainty.covariance;
  Eigen::Matrix<double, 3, 6> motion;
  motion << Eigen::Matrix3d::Identity(), -skew(point_scan - T_cad_scan.inverse().translation());
  return {std::sqrt(std::max(0.0, c.bottomRightCorner<3, 3>().trace())),
          std::sqrt(std::max(0.0, (motion * c * motion.transpose()).trace()))};
}

}  // namespace freeform_inspection
