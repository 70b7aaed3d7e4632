// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/icp.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "median_internal.h"
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace freeform_inspection {
namespace {

Points evenSubset(const Points& points, std::size_t count) {
  if (points.size() <= count) {
    return points;
  }
  Points subset;
  subset.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    subset.push_back(points[i * points.size() / count]);
  }
  return subset;
}

struct Pairs {
  std::vector<Eigen::Vector3d> source;  // moved scan points
  std::vector<Eigen::Vector3d> target;  // closest CAD points
  std::vector<Eigen::Vector3d> normal;  // CAD face normals
  std::vector<double> residual;         // signed (plane) or unsigned (point) distance
  std::vector<double> bulge;            // the curve's bulge out of the face at the target
};

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// The scan points ICP works on (an evenly spread subset), with their normals when given.
struct ScanSample {
  Points points;
  Points normals;  // empty, or one per point (scan frame)
};

ScanSample evenSample(const Points& points, const Points& normals, std::size_t count) {
  ScanSample sample{evenSubset(points, count), Points()};
  if (normals.size() == points.size()) {
    sample.normals = evenSubset(normals, count);
  }
  return sample;
}

// `faces`: each point's face of the previous iteration (−1: none), where its search starts;
// updated to this iteration's. With normals, each point's closest face among those facing its way.
Pairs match(const MeshQuery& cad,
            const ScanSample& sample,
            const Eigen::Isometry3d& T,
            double cutoff,
            const IcpConfig& config,
            std::vector<int>* faces,
            const CurvedSurface& curved) {
  const Points& points = sample.points;
  Points moved(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    moved[i] = T * points[i];
  }
  faces->resize(points.size(), -1);
  Points turned;  // none: every point's nearest face, whatever its normal
  if (config.facing_tolerance_deg < 180.0) {
    for (const Eigen::Vector3d& normal : sample.normals) {
      turned.push_back(T.linear() * normal);
    }
  }
  const std::vector<ClosestPoint> closest = cad.closestFacing(
      moved, turned, std::cos(config.facing_tolerance_deg * kDegree), true, cutoff, *faces);
  const bool point_to_plane = config.point_to_plane;
  Pairs pairs;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    (*faces)[i] = closest[i].face;
    if (!closest[i].found) {
      continue;
    }
    // On the curve the face stands for, when one is given: its bulge out along the face normal
    // (read only then: it is a barycentric evaluation per pair).
    const double bulge = curved.chord != nullptr
                             ? bulgeAt(*curved.chord, cad.mesh(), closest[i].face, closest[i].point)
                             : 0.0;
    const double lift = curved.share * bulge;
    const Eigen::Vector3d target =
        lift != 0.0 ? Eigen::Vector3d(closest[i].point + lift * closest[i].normal)
                    : closest[i].point;
    pairs.source.push_back(moved[i]);
    pairs.target.push_back(target);
    pairs.normal.push_back(closest[i].normal);
    pairs.bulge.push_back(bulge);
    pairs.residual.push_back(point_to_plane ? closest[i].normal.dot(moved[i] - target)
                             : lift != 0.0  ? (moved[i] - target).norm()
                                            : closest[i].distance);
  }
  return pairs;
}

// A step's turn ω and shift t as a rigid motion.
Eigen::Isometry3d motionOf(const Eigen::Vector3d& omega, const Eigen::Vector3d& shift) {
  Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
  if (omega.norm() > 0.0 && omega.allFinite()) {
    step.linear() = Eigen::AngleAxisd(omega.norm(), omega.normalized()).toRotationMatrix();
  }
  step.translation() = shift.allFinite() ? shift : Eigen::Vector3d::Zero();
  return step;
}

// Linearised point-to-plane step: minimise Σ (n·(p + ω×p + t − q))² over (ω, t).
Eigen::Isometry3d pointToPlaneStep(const Pairs& pairs) {
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
  for (std::size_t i = 0; i < pairs.source.size(); ++i) {
    Eigen::Matrix<double, 6, 1> J;
    J << pairs.source[i].cross(pairs.normal[i]), pairs.normal[i];
    A += J * J.transpose();
    b -= J * pairs.residual[i];
  }
  const Eigen::Matrix<double, 6, 1> x = A.ldlt().solve(b);
  return motionOf(x.head<3>(), x.tail<3>());
}

// The same step with the curve's share as a seventh unknown: minimise
// Σ (n·(p + ω×p + t − q) − Δs·e)² (e: each target's bulge). `share_variance`: the share's
// variance per unit variance of the residuals, 1 / (A_ss − A_sp A_pp⁺ A_ps) with the pose
// block's pseudo-inverse, so that a motion the fit leaves free (a round part's turn about its
// axis) does not make the share look unknown.
Eigen::Isometry3d pointToCurveStep(const Pairs& pairs, double* share_step, double* share_variance) {
  Eigen::Matrix<double, 7, 7> A = Eigen::Matrix<double, 7, 7>::Zero();
  Eigen::Matrix<double, 7, 1> b = Eigen::Matrix<double, 7, 1>::Zero();
  for (std::size_t i = 0; i < pairs.source.size(); ++i) {
    Eigen::Matrix<double, 7, 1> J;
    J << pairs.source[i].cross(pairs.normal[i]), pairs.normal[i], -pairs.bulge[i];
    A += J * J.transpose();
    b -= J * pairs.residual[i];
  }
  const Eigen::LDLT<Eigen::Matrix<double, 7, 7>> solver(A);
  const Eigen::Matrix<double, 7, 1> x = solver.solve(b);
  *share_step = std::isfinite(x[6]) ? x[6] : 0.0;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> pose(A.topLeftCorner<6, 6>());
  const Eigen::Matrix<double, 6, 1> coupling = pose.eigenvectors().transpose() * A.col(6).head<6>();
  double held = A(6, 6);
  const double largest = pose.eigenvalues().maxCoeff();
  for (int k = 0; k < 6; ++k) {
    if (pose.eigenvalues()[k] > 1e-9 * largest) {
      held -= coupling[k] * coupling[k] / pose.eigenvalues()[k];
    }
  }
  *share_variance = held > 0.0 ? 1.0 / held : std::numeric_limits<double>::infinity();
  return motionOf(x.head<3>(), x.segment<3>(3));
}

Eigen::Isometry3d pointToPointStep(const Pairs& pairs) {
  Eigen::Matrix3Xd source(3, static_cast<Eigen::Index>(pairs.source.size()));
  Eigen::Matrix3Xd target(3, static_cast<Eigen::Index>(pairs.source.size()));
  for (std::size_t i = 0; i < pairs.source.size(); ++i) {
    source.col(static_cast<Eigen::Index>(i)) = pairs.source[i];
    target.col(static_cast<Eigen::Index>(i)) = pairs.target[i];
  }
  Eigen::Isometry3d step;
  step.matrix() = Eigen::umeyama(source, target, false);
  return step;
}

}  // namespace

std::vector<std::string> validate(const IcpConfig& config) {
  std::vector<std::string> errors;
  if (config.max_iterations < 1) {
    errors.push_back("icp.max_iterations must be at least 1");
  }
  if (!(config.convergence > 0.0 && config.convergence < 1.0)) {
    errors.push_back("icp.convergence must be in (0, 1)");
  }
  if (!(config.still_fraction >= 0.0 && config.still_fraction < 1.0)) {
    errors.push_back("icp.still_fraction must be in [0, 1)");
  }
  if (!(config.sigma_multiple > 0.0 && std::isfinite(config.sigma_multiple))) {
    errors.push_back("icp.sigma_multiple must be a finite value > 0");
  }
  if (!(config.min_cutoff_ratio > 0.0 && config.min_cutoff_ratio <= config.max_cutoff_ratio &&
        std::isfinite(config.max_cutoff_ratio))) {
    errors.push_back("icp.min_cutoff_ratio and icp.max_cutoff_ratio must satisfy 0 < min <= max");
  }
  if (config.max_points < 6) {
    errors.push_back("icp.max_points must be at least 6");
  }
  if (!(config.facing_tolerance_deg > 0.0 && config.facing_tolerance_deg <= 180.0)) {
    errors.push_back("icp.facing_tolerance_deg must be in (0, 180]");
  }
  return errors;
}

namespace {

// measureFit() on points already thinned to max_points, the search starting from `faces`.
IcpResult fitOf(const MeshQuery& cad,
                const ScanSample& sample,
                const Eigen::Isometry3d& pose,
                double cad_diagonal,
                const IcpConfig& config,
                std::vector<int>* faces,
                const CurvedSurface& curved) {
  IcpResult result;
  result.T_cad_scan = pose;
  result.converged = true;
  const double floor = config.min_cutoff_ratio * cad_diagonal;
  const double ceiling = config.max_cutoff_ratio * cad_diagonal;
  // Inliers within 3σ (bounded), their RMS.
  const Pairs pairs = match(cad, sample, pose, ceiling, config, faces, curved);
  std::vector<double> magnitude(pairs.residual.size());
  std::transform(pairs.residual.begin(), pairs.residual.end(), magnitude.begin(), [](double r) {
    return std::abs(r);
  });
  result.sigma = 1.4826 * internal::median(magnitude);
  result.inlier_distance = std::clamp(config.sigma_multiple * result.sigma, floor, ceiling);
  double sum = 0.0;
  std::size_t inliers = 0;
  for (const double m : magnitude) {
    if (m <= result.inlier_distance) {
      sum += m * m;
      ++inliers;
    }
  }
  result.rmse = inliers > 0 ? std::sqrt(sum / static_cast<double>(inliers)) : 0.0;
  result.fitness = sample.points.empty()
                       ? 0.0
                       : static_cast<double>(inliers) / static_cast<double>(sample.points.size());
  return result;
}

}  // namespace

IcpResult measureFit(const MeshQuery& cad,
                     const Points& scan_points,
                     const Eigen::Isometry3d& pose,
                     double cad_diagonal,
                     const IcpConfig& config,
                     const Points& scan_normals,
                     const CurvedSurface& curved) {
  std::vector<int> faces;
  return fitOf(cad,
               evenSample(scan_points, scan_normals, config.max_points),
               pose,
               cad_diagonal,
               config,
               &faces,
               curved);
}

IcpResult refinePose(const MeshQuery& cad,
                     const Points& scan_points,
                     const Eigen::Isometry3d& initial,
                     double initial_cutoff,
                     double cad_diagonal,
                     const IcpConfig& config,
                     const Points& scan_normals,
                     const CurvedSurface& curved) {
  IcpResult result;
  result.T_cad_scan = initial;
  const ScanSample sample = evenSample(scan_points, scan_normals, config.max_points);
  const Points& points = sample.points;
  const double floor = config.min_cutoff_ratio * cad_diagonal;
  const double ceiling = config.max_cutoff_ratio * cad_diagonal;
  double cutoff = std::clamp(initial_cutoff, floor, ceiling);
  double previous_mse = -1.0;
  // The points' centroid and reach, to bound how far a step moves any of them.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) {
    centroid += p / static_cast<double>(points.size());
  }
  double reach = 0.0;
  for (const Eigen::Vector3d& p : points) {
    reach = std::max(reach, (p - centroid).norm());
  }
  std::vector<int> faces;          // each point's closest face, where the next search starts
  CurvedSurface surface = curved;  // its share moves when estimated
  const bool estimate = curved.estimate && curved.chord != nullptr && config.point_to_plane;
  double share_variance = 0.0;
  for (int iteration = 0; iteration < config.max_iterations; ++iteration) {
    const Pairs pairs = match(cad, sample, result.T_cad_scan, cutoff, config, &faces, surface);
    if (pairs.source.size() < 6) {
      result.status =
          Status::failure(StatusCode::kRegistrationFailed,
                          "ICP lost the surface: " + std::to_string(pairs.source.size()) +
                              " scan points within " + std::to_string(cutoff) + " m of the CAD");
      return result;
    }
    double mse = 0.0;
    for (const double r : pairs.residual) {
      mse += r * r / static_cast<double>(pairs.residual.size());
    }
    double share_step = 0.0;
    const Eigen::Isometry3d step =
        estimate ? pointToCurveStep(pairs, &share_step, &share_variance)
                 : (config.point_to_plane ? pointToPlaneStep(pairs) : pointToPointStep(pairs));
    surface.share += share_step;
    // No point moves farther than the step moves the centroid plus its turn times the reach.
    const Eigen::Vector3d moved_centroid = result.T_cad_scan * centroid;
    const double largest_move = Eigen::AngleAxisd(step.linear()).angle() * reach +
                                (step * moved_centroid - moved_centroid).norm();
    result.T_cad_scan = step * result.T_cad_scan;
    result.iterations = iteration + 1;
    // The cut-off follows the residual: 3 robust σ of the pairs, never growing.
    std::vector<double> magnitude(pairs.residual.size());
    std::transform(pairs.residual.begin(), pairs.residual.end(), magnitude.begin(), [](double r) {
      return std::abs(r);
    });
    result.sigma = 1.4826 * internal::median(magnitude);
    cutoff = std::clamp(std::min(cutoff, config.sigma_multiple * result.sigma), floor, ceiling);
    if (estimate) {
      // Pairs are not trimmed inside the largest bulge: a cut-off about the current share
      // would keep the points that side with it, and the share would stay where it started.
      cutoff = std::max(cutoff, std::min(surface.chord->max, ceiling));
    }
    // eq. 15 (relative change of the mean squared error), or a step too small to matter. On
    // noise-free data the error keeps halving long after the pose has stopped moving. On a noisy
    // scan the pairs trade faces between iterations and the error jitters by 1e-4 of itself for
    // ever, never meeting eq. 15: the pose has settled when the error rose while the step moved
    // no point by a hundredth of the noise. (A small step alone is not enough: far from the pose
    // the residual is wide, and steady small steps still lead somewhere.)
    const bool settled =
        previous_mse >= 0.0 && std::abs(previous_mse - mse) < config.convergence * previous_mse;
    const bool jitter = previous_mse >= 0.0 && mse >= previous_mse &&
                        largest_move < config.still_fraction * result.sigma;
    const bool still = jitter || largest_move < 1e-8 * cad_diagonal;
    if (settled || still) {
      result.converged = true;
      break;
    }
    previous_mse = mse;
  }
  const IcpResult fit =
      fitOf(cad, sample, result.T_cad_scan, cad_diagonal, config, &faces, surface);
  if (estimate) {
    result.curve_share = surface.share;
    result.curve_share_error = fit.sigma * std::sqrt(std::max(share_variance, 0.0));
  }
  result.sigma = fit.sigma;
  result.inlier_distance = fit.inlier_distance;
  result.rmse = fit.rmse;
  result.fitness = fit.fitness;
  if (!result.converged) {
    result.status = Status::failure(
        StatusCode::kNotConverged,
        "ICP did not converge in " + std::to_string(config.max_iterations) + " iterations");
  }
  return result;
}

CurveShare curveShareAt(const MeshQuery& cad,
                        const ChordError& chord,
                        const Points& scan_points,
                        const Eigen::Isometry3d& pose,
                        double band,
                        const IcpConfig& config,
                        const Points& scan_normals) {
  CurveShare out;
  if (!(chord.max > 0.0) || !(band > 0.0) || chord.bulge.size() != cad.mesh().faces.size()) {
    return out;
  }
  std::vector<int> faces;
  IcpConfig plane = config;
  plane.point_to_plane = true;  // signed residuals
  CurvedSurface bulges;
  bulges.chord = &chord;  // share 0: the faces, with each target's bulge recorded
  const Pairs pairs = match(cad,
                            evenSample(scan_points, scan_normals, config.max_points),
                            pose,
                            band + chord.max,
                            plane,
                            &faces,
                            bulges);
  // r = s·e + noise over every pair within the band widened by the largest bulge: a window
  // that depended on r would lean towards one answer (a band about the faces or about the
  // curve keeps the noise that sides with it).
  double re = 0.0;
  double ee = 0.0;
  for (std::size_t i = 0; i < pairs.source.size(); ++i) {
    re += pairs.residual[i] * pairs.bulge[i];
    ee += pairs.bulge[i] * pairs.bulge[i];
  }
  if (!(ee > 0.0) || pairs.source.size() < 6) {
    return out;
  }
  out.share = re / ee;
  std::vector<double> misfit;
  misfit.reserve(pairs.source.size());
  for (std::size_t i = 0; i < pairs.source.size(); ++i) {
    misfit.push_back(std::abs(pairs.residual[i] - out.share * pairs.bulge[i]));
  }
  out.error = 1.4826 * internal::median(std::move(misfit)) / std::sqrt(ee);
  return out;
}

Eigen::Isometry3d WeakMotion::by(double distance) const {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d turn = distance * rotation;
  if (turn.norm() > 0.0 && turn.allFinite()) {
    motion.linear() = Eigen::AngleAxisd(turn.norm(), turn.normalized()).toRotationMatrix();
  }
  motion.translation() = centre - motion.linear() * centre + distance * translation;
  return motion;
}

std::vector<WeakMotion> weakestMotions(const MeshQuery& cad,
                                       const Points& points,
                                       const Eigen::Isometry3d& pose,
                                       double max_distance,
                                       int count) {
  Points moved;
  Points normals;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = pose * p;
    const ClosestPoint closest = cad.closest(q, max_distance);
    if (closest.found) {
      moved.push_back(q);
      normals.push_back(closest.normal);
    }
  }
  std::vector<WeakMotion> motions;
  if (moved.size() < 6 || count < 1) {
    return motions;
  }
  const auto n = static_cast<double>(moved.size());
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& q : moved) {
    centre += q / n;
  }
  double spread = 0.0;
  for (const Eigen::Vector3d& q : moved) {
    spread += (q - centre).squaredNorm() / n;
  }
  const double radius = std::sqrt(spread);
  if (!(radius > 0.0)) {
    return motions;
  }
  // The same Jacobian as pointToPlaneStep(), its turn part in metres of motion at the radius.
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  for (std::size_t i = 0; i < moved.size(); ++i) {
    Eigen::Matrix<double, 6, 1> J;
    J << (moved[i] - centre).cross(normals[i]) / radius, normals[i];
    A += J * J.transpose() / n;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> solver(A);
  for (int k = 0; k < std::min(count, 6); ++k) {
    const Eigen::Matrix<double, 6, 1> v = solver.eigenvectors().col(k);
    WeakMotion motion;
    motion.rotation = v.head<3>() / radius;
    motion.translation = v.tail<3>();
    motion.centre = centre;
    motion.stiffness = std::max(solver.eigenvalues()[k], 0.0);
    motions.push_back(motion);
  }
  return motions;
}

}  // namespace freeform_inspection
