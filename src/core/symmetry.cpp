// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/symmetry.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Eigenvalues>

#include "freeform_inspection/correspondence.h"
#include "freeform_inspection/features.h"
#include "freeform_inspection/global_registration.h"
#include "freeform_inspection/icp.h"

namespace freeform_inspection {
namespace {

// The area-weighted centroid of a surface graph, its principal axes (columns) and the spread
// along each [m].
struct PrincipalFrame {
  Eigen::Vector3d centroid;
  Eigen::Matrix3d axes;
  Eigen::Vector3d spread;
};

// The area-weighted centroid of the cells; empty for a graph without area.
std::optional<Eigen::Vector3d> areaCentroid(const SurfaceGraph& graph) {
  double area = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (std::size_t c = 0; c < graph.size(); ++c) {
    centroid += graph.area[c] * graph.centroids[c];
    area += graph.area[c];
  }
  if (!(area > 0.0)) {
    return std::nullopt;
  }
  return Eigen::Vector3d(centroid / area);
}

// Empty for a graph without area.
std::optional<PrincipalFrame> principalFrame(const SurfaceGraph& graph) {
  const std::optional<Eigen::Vector3d> centroid = areaCentroid(graph);
  if (!centroid) {
    return std::nullopt;
  }
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t c = 0; c < graph.size(); ++c) {
    const Eigen::Vector3d d = graph.centroids[c] - *centroid;
    covariance += graph.area[c] * d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  return PrincipalFrame{
      *centroid, solver.eigenvectors(), solver.eigenvalues().cwiseMax(0.0).cwiseSqrt()};
}

// The principal axes (columns) of the cells' normals, eigenvectors of Σ a n nᵀ: the directions of
// a sheet part's walls and faces. Unlike the axes of the points' spread, these stay put when an
// appendage on one side (a wider flange) shifts the mass. Empty without normals.
std::optional<Eigen::Matrix3d> normalAxes(const SurfaceGraph& graph) {
  if (graph.normals.size() != graph.size()) {
    return std::nullopt;
  }
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (std::size_t c = 0; c < graph.size(); ++c) {
    scatter += graph.area[c] * graph.normals[c] * graph.normals[c].transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  return solver.eigenvectors();
}

// The motion turning by `rotation` about `centroid`.
Eigen::Isometry3d turnAbout(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& centroid) {
  Eigen::Isometry3d S = Eigen::Isometry3d::Identity();
  S.linear() = rotation;
  S.translation() = centroid - rotation * centroid;
  return S;
}

// Rotations about the principal axes of the model's surface (through its centroid) by multiples
// of 30°: the motions near-symmetric parts (flanges, tubes, blades) are confused by. Each is
// only a starting point; ICP takes it to the nearest true self-match, if any.
std::vector<Eigen::Isometry3d> principalAxisRotations(const SurfaceGraph& graph) {
  std::vector<Eigen::Isometry3d> motions;
  const std::optional<PrincipalFrame> frame = principalFrame(graph);
  if (!frame) {
    return motions;
  }
  for (int axis = 0; axis < 3; ++axis) {
    // Turns by 30° only about an axis the part is nearly round about (the other two spreads
    // within 25 %); about any other axis only the half turn can map the part onto itself.
    const double a = frame->spread[(axis + 1) % 3];
    const double b = frame->spread[(axis + 2) % 3];
    const bool round = std::abs(a - b) <= 0.25 * std::max(a, b);
    for (int step = round ? 1 : 6; step < (round ? 12 : 7); ++step) {
      const Eigen::AngleAxisd rotation(step * 3.14159265358979323846 / 6.0, frame->axes.col(axis));
      motions.push_back(turnAbout(rotation.toRotationMatrix(), frame->centroid));
    }
  }
  return motions;
}

// Signed permutations of `axes` (columns) with determinant +1, about `centroid`: the rotation
// group of a cube set along them (23, the identity left out).
std::vector<Eigen::Isometry3d> cubeTurns(const Eigen::Matrix3d& axes,
                                         const Eigen::Vector3d& centroid) {
  std::vector<Eigen::Isometry3d> turns;
  const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& order : orders) {
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d Q = Eigen::Matrix3d::Zero();
      for (int row = 0; row < 3; ++row) {
        Q(row, order[row]) = ((signs >> row) & 1) != 0 ? -1.0 : 1.0;
      }
      if (Q.determinant() > 0.0 && !Q.isIdentity()) {
        turns.push_back(turnAbout(axes * Q * axes.transpose(), centroid));
      }
    }
  }
  return turns;
}

}  // namespace

std::vector<Symmetry> findSymmetries(const DescriptorResult& cad,
                                     const MeshQuery& query,
                                     double cell_size,
                                     double diagonal,
                                     double min_score) {
  std::vector<Symmetry> symmetries;
  if (!cad.status.ok() || cad.graph.size() < 3 || !query.status().ok()) {
    return symmetries;
  }
  const double r_max = cad.radii.back();
  const FeatureResult features =
      selectFeatures(cad.graph.centroids, cad.cell_values, r_max, FeatureConfig());
  const CorrespondenceConfig correspondence;
  const CorrespondenceResult candidates = findCandidates(cad.cell_values,
                                                         features.cells,
                                                         cad.cell_values,
                                                         cad.graph.centroids,
                                                         cell_size,
                                                         correspondence);
  GlobalRegistrationConfig config;
  config.verified_hypotheses = 64;  // self-matches are few; the scan's default is generous
  config.max_fits = 20000;
  config.verification_points = 600;
  // A failed self-registration still leaves the principal-axis starts below.
  const GlobalRegistrationResult global =
      registerGlobally(cad.graph, cad.graph, candidates, query, cell_size, r_max, config, true);
  // The CAD's normals are its faces' outward normals: a motion that turns the model inside
  // out against itself is no symmetry.
  const VerificationSet set = makeVerificationSet(cad.graph, config.verification_points, true);
  const Eigen::Vector3d reference = set.centroid();
  const double truncation = config.verification_distance_cells * cell_size;
  IcpConfig config_icp;
  config_icp.max_iterations = 15;
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Isometry3d> starts = principalAxisRotations(cad.graph);
  for (const PoseHypothesis& hypothesis : global.hypotheses) {
    if (hypothesis.score >= 0.5 * min_score) {
      starts.push_back(hypothesis.T_cad_scan);
    }
  }
  // Refine every start (in parallel: one region for all of them), then keep the new ones.
  std::vector<Symmetry> refined(starts.size());
  const auto count = static_cast<long>(starts.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (long i = 0; i < count; ++i) {
    const Eigen::Isometry3d& start = starts[static_cast<std::size_t>(i)];
    if (!separatePoses(identity, start, reference, cell_size)) {
      continue;
    }
    const IcpResult icp = refinePose(query, set.points, start, truncation, diagonal, config_icp);
    const Eigen::Isometry3d S = icp.usable() ? icp.T_cad_scan : start;
    refined[static_cast<std::size_t>(i)] = {
        S, verificationScore(S, set, query, truncation, config.normal_tolerance_deg)};
  }
  for (const Symmetry& candidate : refined) {
    const bool is_new = separatePoses(identity, candidate.S, reference, cell_size) &&
                        std::all_of(symmetries.begin(), symmetries.end(), [&](const Symmetry& s) {
                          return separatePoses(s.S, candidate.S, reference, cell_size);
                        });
    if (candidate.score >= min_score && is_new) {
      symmetries.push_back(candidate);
    }
  }
  std::stable_sort(symmetries.begin(), symmetries.end(), [](const Symmetry& a, const Symmetry& b) {
    return a.score > b.score;
  });
  return symmetries;
}

std::vector<Eigen::Isometry3d> principalFrameTurns(const SurfaceGraph& graph) {
  const std::optional<PrincipalFrame> frame = principalFrame(graph);
  return frame ? cubeTurns(frame->axes, frame->centroid) : std::vector<Eigen::Isometry3d>();
}

std::vector<Eigen::Isometry3d> normalFrameTurns(const SurfaceGraph& graph) {
  const std::optional<Eigen::Vector3d> centroid = areaCentroid(graph);
  const std::optional<Eigen::Matrix3d> axes = normalAxes(graph);
  return centroid && axes ? cubeTurns(*axes, *centroid) : std::vector<Eigen::Isometry3d>();
}

}  // namespace freeform_inspection
