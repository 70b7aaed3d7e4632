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

constexpr double kDegree = 3.14159265358979323846 / 180.0;

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

// The directions of a walled part's flat faces (columns, right-handed): the normal direction
// (either sign) with the most cell area within kWallConeDeg of it, then the most populated one
// square to it, then their cross product. Where two walls carry about the same area the
// scatter's eigenvectors (normalAxes) may lie anywhere between them: a machined L-block's bores
// and chamfer tilted its x and y axes by 16°, and the half turn that swaps its legs was never
// tried. Empty unless two walls square to each other hold kMinWallShare of the area each (a disc
// has one: its rim's normals spread all round).
std::optional<Eigen::Matrix3d> wallAxes(const SurfaceGraph& graph) {
  constexpr double kWallConeDeg = 10.0;
  constexpr double kMinWallShare = 0.1;
  constexpr std::size_t kCandidates = 512;  // cell normals tried as wall directions
  if (graph.normals.size() != graph.size() || graph.size() == 0) {
    return std::nullopt;
  }
  const double cone = std::cos(kWallConeDeg * kDegree);
  const double square = std::sin(kWallConeDeg * kDegree);
  double total = 0.0;
  for (const double area : graph.area) {
    total += area;
  }
  // The area within the cone about ±d, and its normals' area-weighted mean turned to d's side.
  const auto wall = [&](const Eigen::Vector3d& d) {
    double area = 0.0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t c = 0; c < graph.size(); ++c) {
      const double along = graph.normals[c].dot(d);
      if (std::abs(along) > cone) {
        area += graph.area[c];
        sum += (along > 0.0 ? graph.area[c] : -graph.area[c]) * graph.normals[c];
      }
    }
    return std::make_pair(area, Eigen::Vector3d(sum.normalized()));
  };
  const std::size_t stride = std::max<std::size_t>(1, graph.size() / kCandidates);
  // The most populated wall, among directions square to `across` when one is given.
  const auto mostPopulated = [&](const Eigen::Vector3d* across) {
    std::pair<double, Eigen::Vector3d> best{0.0, Eigen::Vector3d::Zero()};
    for (std::size_t c = 0; c < graph.size(); c += stride) {
      const Eigen::Vector3d& d = graph.normals[c];
      if (d.allFinite() && (across == nullptr || std::abs(d.dot(*across)) < square)) {
        const auto candidate = wall(d);
        if (candidate.first > best.first) {
          best = candidate;
        }
      }
    }
    return best;
  };
  const auto first = mostPopulated(nullptr);
  if (!(first.first >= kMinWallShare * total)) {
    return std::nullopt;
  }
  const auto second = mostPopulated(&first.second);
  if (!(second.first >= kMinWallShare * total)) {
    return std::nullopt;
  }
  const Eigen::Vector3d x = first.second;
  const Eigen::Vector3d y = (second.second - second.second.dot(x) * x).normalized();
  Eigen::Matrix3d axes;
  axes << x, y, x.cross(y);
  return axes.allFinite() ? std::optional<Eigen::Matrix3d>(axes) : std::nullopt;
}

// True when every axis of `a` lies within a few degrees of an axis of `b` (either sign): the same
// cube, whose turns need not be tried twice.
bool sameCube(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const double close = std::cos(3.0 * kDegree);
  for (int i = 0; i < 3; ++i) {
    if ((b.transpose() * a.col(i)).cwiseAbs().maxCoeff() < close) {
      return false;
    }
  }
  return true;
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

// How far a self-match is searched along its weakest motion, as a share of the diagonal, in
// steps of one cell. A prismatic part's self-match slides along its axis without leaving the
// surface, so ICP stops wherever the start put it: the hat channel's half turn came 40 mm (a
// quarter of its length) off the turn that lays it best onto itself, and a scan's twin of a
// turned pose then missed the truth by as much.
constexpr double kSlideSearchShare = 0.3;

// `candidate` moved to the best place along its weakest motion (scored without ICP, one cell
// apart), then refined there; unchanged unless that scores higher.
Symmetry slidToBest(const Symmetry& candidate,
                    const VerificationSet& set,
                    const MeshQuery& query,
                    double truncation,
                    double cell_size,
                    double diagonal,
                    double normal_tolerance_deg,
                    const IcpConfig& config_icp) {
  const std::vector<WeakMotion> motions =
      weakestMotions(query, set.points, candidate.S, truncation, 1);
  if (motions.empty()) {
    return candidate;
  }
  const auto steps = static_cast<int>(std::ceil(kSlideSearchShare * diagonal / cell_size));
  Eigen::Isometry3d best_start = candidate.S;
  double best_start_score = candidate.score;
  for (int step = -steps; step <= steps; ++step) {
    if (step == 0) {
      continue;
    }
    const Eigen::Isometry3d start = motions.front().by(step * cell_size) * candidate.S;
    const double score = verificationScore(start, set, query, truncation, normal_tolerance_deg);
    if (score > best_start_score) {
      best_start = start;
      best_start_score = score;
    }
  }
  if (best_start.isApprox(candidate.S)) {
    return candidate;
  }
  const IcpResult icp = refinePose(query, set.points, best_start, truncation, diagonal, config_icp);
  const Eigen::Isometry3d S = icp.usable() ? icp.T_cad_scan : best_start;
  const double score = verificationScore(S, set, query, truncation, normal_tolerance_deg);
  return score > candidate.score ? Symmetry{S, score} : candidate;
}

// The motions scoring at least `floor`, best first, each apart from the identity and from every
// better one (the best of each group of starts that ended on one self-match). Deterministic.
std::vector<Symmetry> distinctBestFirst(std::vector<Symmetry> candidates,
                                        double floor,
                                        const Eigen::Vector3d& reference,
                                        double cell_size) {
  std::stable_sort(candidates.begin(), candidates.end(), [](const Symmetry& a, const Symmetry& b) {
    return a.score > b.score;
  });
  std::vector<Symmetry> distinct;
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  for (const Symmetry& candidate : candidates) {
    if (candidate.score >= floor && separatePoses(identity, candidate.S, reference, cell_size) &&
        std::all_of(distinct.begin(), distinct.end(), [&](const Symmetry& s) {
          return separatePoses(s.S, candidate.S, reference, cell_size);
        })) {
      distinct.push_back(candidate);
    }
  }
  return distinct;
}

}  // namespace

std::vector<Symmetry> findSymmetries(const DescriptorResult& cad,
                                     const MeshQuery& query,
                                     double cell_size,
                                     double diagonal,
                                     double min_score) {
  if (!cad.status.ok() || cad.graph.size() < 3 || !query.status().ok()) {
    return {};
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
  config.refined_hypotheses = config.verified_hypotheses;  // every score above min_score counts
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
  // Refine every start (in parallel: one region for all of them); slide the distinct ones that
  // come within half the threshold (many starts end on one self-match, so this is a few), then
  // keep the distinct ones that meet it.
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
  std::vector<Symmetry> slid = distinctBestFirst(refined, 0.5 * min_score, reference, cell_size);
  const auto slid_count = static_cast<long>(slid.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (long i = 0; i < slid_count; ++i) {
    Symmetry& candidate = slid[static_cast<std::size_t>(i)];
    candidate = slidToBest(candidate,
                           set,
                           query,
                           truncation,
                           cell_size,
                           diagonal,
                           config.normal_tolerance_deg,
                           config_icp);
  }
  return distinctBestFirst(slid, min_score, reference, cell_size);
}

std::vector<Eigen::Isometry3d> principalFrameTurns(const SurfaceGraph& graph) {
  const std::optional<PrincipalFrame> frame = principalFrame(graph);
  return frame ? cubeTurns(frame->axes, frame->centroid) : std::vector<Eigen::Isometry3d>();
}

std::vector<Eigen::Isometry3d> normalFrameTurns(const SurfaceGraph& graph) {
  const std::optional<Eigen::Vector3d> centroid = areaCentroid(graph);
  const std::optional<Eigen::Matrix3d> axes = normalAxes(graph);
  if (!centroid || !axes) {
    return {};
  }
  std::vector<Eigen::Isometry3d> turns = cubeTurns(*axes, *centroid);
  const std::optional<Eigen::Matrix3d> walls = wallAxes(graph);
  if (walls && !sameCube(*walls, *axes)) {
    const std::vector<Eigen::Isometry3d> wall_turns = cubeTurns(*walls, *centroid);
    turns.insert(turns.end(), wall_turns.begin(), wall_turns.end());
  }
  return turns;
}

}  // namespace freeform_inspection
