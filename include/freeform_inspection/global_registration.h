// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/correspondence.h"
#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/surface_graph.h"
#include "freeform_inspection/types.h"

/// @file global_registration.h
/// Global registration (paper §2.6, §3.6.1) with the triangle check of §3.5: feature triplets
/// whose candidate triplets form congruent triangles give rigid fits (Kabsch/Umeyama); each fit
/// is scored by eq. 14 over all features; the best fits are then verified against the whole
/// scan (truncated distance to the CAD surface with normal agreement), so a wrong triplet or a
/// flip of a near-symmetric part loses to the right pose.

namespace freeform_inspection {

/// Global-registration settings. Lengths in surface-graph cells (the descriptor resolution).
struct GlobalRegistrationConfig {
  double pair_tolerance_cells = 3.0;   ///< |d_scan − d_CAD| allowed between two correspondences
  double normal_tolerance_deg = 40.0;  ///< normal angles that must agree (pair and fit checks)
  double min_side_ratio = 0.3;         ///< triplet sides at least this × r_max (a stable fit)
  std::size_t max_fits = 60000;        ///< cap on rigid fits evaluated (rarest triplets first)
  int verified_hypotheses = 128;       ///< best fits by eq. 14 verified against the whole scan
  std::size_t verification_points = 1500;    ///< scan cells used for verification (at most)
  double verification_distance_cells = 2.5;  ///< truncation distance of the verification score
  /// Best verified poses refined by ICP before the final choice. Only these need their exact
  /// scores: a hypothesis that verification shows cannot rank among them is dropped early.
  int refined_hypotheses = 12;
  /// Two distinct refined poses whose scores are within this ratio are reported as ambiguous.
  double ambiguity_ratio = 0.93;
  double min_score = 0.4;    ///< a final verification score below this is a failed registration
  double min_fitness = 0.6;  ///< a final ICP fitness below this is a failed registration
  /// A pose whose residual σ exceeds this × the scan's own noise (at least 0.1 % of L) while it
  /// leaves more than 1 − `residual_fitness` of the scan outside the inliers is not trusted: a
  /// slid or turned pose fits part of the scan and stretches the residual. (A right pose on a
  /// part with a smooth form error has a wide residual too, but nearly no point beyond 3σ; one
  /// with outliers or local defects leaves points out, but its robust σ stays the noise.)
  double max_residual_ratio = 1.5;
  double residual_fitness = 0.99;
  /// A pose that leaves more than 1 − this of the scan's *surface* (linked cells, not scattered
  /// outliers) farther than the inlier distance from the CAD is not trusted: a flipped or slid
  /// pose leaves a connected patch off the part. A scan with more foreign surface than that
  /// (fixture, table) must be cropped, or this lowered (surface_support.h).
  double min_surface_on_cad = 0.8;
};

/// @brief One message per invalid field; empty when valid.
std::vector<std::string> validate(const GlobalRegistrationConfig& config);

/// A candidate pose.
struct PoseHypothesis {
  Eigen::Isometry3d T_cad_scan = Eigen::Isometry3d::Identity();
  int features_explained = 0;  ///< features within the pair tolerance of one of their candidates
  double error = 0.0;          ///< eq. 14 (truncated, nearest candidate) [m^2]
  double score = 0.0;          ///< verification score in [0, 1]: share of the scan explained
  int feature_triplet[3] = {-1, -1, -1};  ///< indices into the feature list
  int cad_triplet[3] = {-1, -1, -1};      ///< CAD cells they were matched to
};

/// Result of the global stage.
struct GlobalRegistrationResult {
  Status status;
  /// Verified, distinct, best score first: those that can rank among the `refined_hypotheses`
  /// best (config), each with its exact score.
  std::vector<PoseHypothesis> hypotheses;
  std::size_t consistent_triplets = 0;  ///< triplets that passed the triangle check
  std::size_t correspondences = 0;      ///< distinct (feature, CAD cell) pairs in those triplets
};

/// Points (with unit outward normals) a pose is verified on.
struct VerificationSet {
  Points points;   ///< [m] scan frame
  Points normals;  ///< unit, outward (zero where unknown: no normal check)
  /// The normals are known to point out of the material (a scanner's normals, a mesh's
  /// winding): compared signed, so a pose that puts the scan on the wrong side of a wall (a
  /// flip) explains nothing. Otherwise only their lines are compared.
  bool oriented = false;

  /// Mean of the points: the reference point that tells distinct poses apart.
  Eigen::Vector3d centroid() const;
};

/// @brief Up to `count` scan cells, spread evenly over the cell list (deterministic).
VerificationSet makeVerificationSet(const SurfaceGraph& scan,
                                    std::size_t count,
                                    bool oriented = false);

/// @brief The same cells as makeVerificationSet(), each placed at the mean of its points'
/// `positions` (indexed like scan.point_cell: a noisy cloud's points moved onto their fitted
/// surfaces) instead of at its centroid, which is a mean of a few measured points and keeps most
/// of their noise. A cell none of whose points has a position keeps its centroid.
VerificationSet makeVerificationSet(const SurfaceGraph& scan,
                                    std::size_t count,
                                    bool oriented,
                                    const Points& positions);

/// @brief Share of the set the pose explains: mean over points of max(0, 1 − d²/τ²) where d is
/// the distance to the CAD surface, counted only where the normals agree.
/// @param floor once the score is sure to end below it, the search stops and returns a bound
/// that is below it too (the score itself when it never is).
double verificationScore(const Eigen::Isometry3d& T_cad_scan,
                         const VerificationSet& set,
                         const MeshQuery& cad,
                         double truncation,
                         double normal_tolerance_deg,
                         double floor = -std::numeric_limits<double>::infinity());

/// @brief Per point of the set, 1 − d²/τ² where d is the distance to the nearest CAD surface that
/// faces the way the point's normal does (MeshQuery::closestFacing), 0 where none lies within τ.
/// The evidence scanPrefers() weighs: unlike verificationScore()'s nearest surface, it does not
/// disown noisy points on a wall thinner than the noise, which turn up nearer its far side and
/// would make two poses differ by where the noise fell (a flange's 120° twin preferred 106:36).
std::vector<double> verificationTerms(const Eigen::Isometry3d& T_cad_scan,
                                      const VerificationSet& set,
                                      const MeshQuery& cad,
                                      double truncation,
                                      double normal_tolerance_deg);

/// @brief Whether the scan itself tells pose `a` from pose `b` (terms from verificationTerms()):
/// the points only `a` explains are at least 1 % of all, outnumber those only `b` explains at
/// least twice, and by three standard deviations of a coin toss between the two (a sign test).
/// A symmetric part's twins explain the same points but for the noise; the twin of a
/// near-symmetric part that the view does tell apart leaves the differing feature unexplained.
bool scanPrefers(const std::vector<double>& a, const std::vector<double>& b);

/// @brief The sign test of scanPrefers() alone: the points only `a` explains outnumber those
/// only `b` explains by `sigmas` standard deviations of a coin toss between the two, and are at
/// least `min_share` of all points, without scanPrefers' ratio. Evidence that leans `a`'s way,
/// too weak to decide on its own.
bool scanLeans(const std::vector<double>& a,
               const std::vector<double>& b,
               double sigmas,
               double min_share = 0.0);

/// @brief How far pose `b` lies from pose `a`: the angle of their relative turn and the distance
/// between the places they move `reference` (scan frame) to.
struct PoseDifference {
  double angle = 0.0;  ///< [rad], in [0, π]
  double shift = 0.0;  ///< [m]
};
PoseDifference poseDifference(const Eigen::Isometry3d& a,
                              const Eigen::Isometry3d& b,
                              const Eigen::Vector3d& reference);

/// @brief True when two poses differ by more than `angle_deg` or move `reference` (scan frame)
/// by more than `distance`.
bool distinctPoses(const Eigen::Isometry3d& a,
                   const Eigen::Isometry3d& b,
                   const Eigen::Vector3d& reference,
                   double angle_deg,
                   double distance);

/// @brief The poses a result lists apart (its contenders and alternatives, a model's
/// symmetries): more than 10° or 3 cells of `cell_size` apart at `reference`. Finer differences
/// are one pose that ICP has not finished moving.
bool separatePoses(const Eigen::Isometry3d& a,
                   const Eigen::Isometry3d& b,
                   const Eigen::Vector3d& reference,
                   double cell_size);

/// @brief How far apart `a` and `b` are in units of that separation: the larger of their relative
/// turn over 10° and the shift of `reference` over 3 cells (above 1 where separatePoses()).
double poseGap(const Eigen::Isometry3d& a,
               const Eigen::Isometry3d& b,
               const Eigen::Vector3d& reference,
               double cell_size);

/// @brief Whether a rival pose found at `found`, which refinement moved to `refined`, came onto
/// `best`: within the separation of distinct poses of it (poseGap() ≤ 1) and with at least `share`
/// of its gap to it closed, so that a rival found just beyond the separation and barely moved is
/// not taken for the best's own.
bool refinedOnto(const Eigen::Isometry3d& best,
                 const Eigen::Isometry3d& found,
                 const Eigen::Isometry3d& refined,
                 const Eigen::Vector3d& reference,
                 double cell_size,
                 double share);

/// @brief Features whose centre, moved by the pose, lies within `tolerance` [m] of one of their
/// CAD candidates: the correspondences the pose confirms.
int countExplainedFeatures(const Eigen::Isometry3d& T_cad_scan,
                           const SurfaceGraph& scan,
                           const SurfaceGraph& cad,
                           const CorrespondenceResult& candidates,
                           double tolerance);

/// @brief Runs the global stage.
/// @param scan scan cells (features and candidates index them)
/// @param cad CAD cells
/// @param cell_size [m], r_max [m]
/// @param oriented_normals the scan's normals point out of the material (VerificationSet)
GlobalRegistrationResult registerGlobally(const SurfaceGraph& scan,
                                          const SurfaceGraph& cad,
                                          const CorrespondenceResult& candidates,
                                          const MeshQuery& cad_mesh,
                                          double cell_size,
                                          double r_max,
                                          const GlobalRegistrationConfig& config,
                                          bool oriented_normals = false);

}  // namespace freeform_inspection
