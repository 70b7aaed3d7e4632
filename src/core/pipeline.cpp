// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <utility>

#include "median_internal.h"
#include "pipeline_internal.h"
#include "turn_votes_internal.h"

#include "freeform_inspection/datum_alignment.h"
#include "freeform_inspection/geodesic.h"
#include "freeform_inspection/organized_mesh.h"
#include "freeform_inspection/scan_noise.h"
#include "freeform_inspection/surface_support.h"
#include "freeform_inspection/symmetry.h"
#include "freeform_inspection/view_hints.h"

namespace freeform_inspection {
namespace {

using internal::fitToAlignedRegions;
using internal::formatLength;
using internal::judge;
using internal::measurePart;

using Clock = std::chrono::steady_clock;
constexpr double kPi = 3.14159265358979323846;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Organized scans (range images) carry their connectivity: triangulate on the grid, before the
// non-finite pixels are removed, so the scan is a mesh like the CAD.
CleanScanResult cleanWithGridFaces(const Scan& scan,
                                   const BoundingBox& model_bounds,
                                   const InputConfig& config) {
  if (!scan.isOrganized() || !scan.faces.empty()) {
    return cleanScan(scan, model_bounds, config);
  }
  Scan meshed = scan;
  meshed.faces =
      triangulateOrganizedGrid(scan.points, scan.width, scan.height, OrganizedMeshConfig());
  return cleanScan(meshed, model_bounds, config);
}

// The cleaned scan without the points of its supports (faces through them dropped), checked
// again like any scan: what is left must still fix a pose.
CleanScanResult withoutSupports(const Scan& cleaned,
                                const SupportResult& supports,
                                const BoundingBox& model_bounds,
                                const InputConfig& config) {
  Scan kept = cleaned;
  for (std::size_t i = 0; i < kept.points.size(); ++i) {
    if (supports.on_support[i] != 0) {
      kept.points[i] = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    }
  }
  return cleanScan(kept, model_bounds, config);
}

// Stage timings, and the caller's progress callback between stages.
struct Stopwatch {
  InspectionResult* result;
  const ProgressCallback* progress = nullptr;
  Clock::time_point start = Clock::now();
  void lap(const std::string& stage) {
    result->timings.push_back({stage, secondsSince(start)});
    start = Clock::now();
  }
  // False, with the status set, when the caller asked to stop before `stage`.
  bool proceed(const std::string& stage, double fraction) {
    if (progress == nullptr || !*progress || (*progress)(stage, fraction)) {
      return true;
    }
    result->status =
        Status::failure(StatusCode::kCancelled, "inspection cancelled before stage " + stage);
    return false;
  }
  // Ends the ICP stage: false, with the status set, when ICP left no usable pose or the caller
  // asked to stop before the verification.
  bool icpDone(const IcpResult& icp) {
    lap("icp");
    if (!icp.usable()) {
      result->status = icp.status;
      return false;
    }
    return proceed("verification", 0.8);
  }
};

// How the scan is brought onto the CAD: searched (inspect), refined from a given pose
// (inspectFrom) or inspected at it as it is (inspectAt).
struct Alignment {
  enum class Mode { kSearch, kRefine, kFixed };
  Mode mode = Mode::kSearch;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // scan → CAD; unused when searched
};

// A caller's initial pose must be a rotation to this (largest entry of |RᵀR − I|): a pose pasted
// from a report's 17 significant digits is one to 1e-15, a scaled one is not.
constexpr double kInitialPoseRigidity = 1e-6;

// A pose that leaves more than this share of the scan's surface off the CAD is retried from
// other starts (registerScan, probeStarts): a right pose of a clean scan explains all of it but
// for its noise tails (0.99-1.0 for the scans of the registration table).
constexpr double kProbeBelowSurface = 0.99;
// Below this share the turns of turnStarts() are tried as well, as they are and where the
// features' votes place them, and the best poses found are probed in turn. Right poses of
// camera views at 0.5 % noise put 0.91-1.0 there, so most scans skip those refinements (92
// turns, up to 138 where the walls' frames differ from the normals' axes, up to 32 placed by the
// features and 8 by the surface, 14 probes about each of the 3 best rivals); a turn only wins
// where the scan sides with it.
constexpr double kRetryBelowSurface = 0.95;
// From there up to kProbeBelowSurface, the half turns about the CAD's wall directions alone
// (the 9 half turns of each frame normalFrameTurns gives): a bent sheet's view with its legs
// swapped explains 98 % of itself, and the probes do not turn it (docs/registration.md, "Half
// turns about the walls up to 99 %").
// Every turn there made camera views, whose right poses often put 0.95-0.99 on the CAD,
// 1.4-2.8x slower; the half turns cost them 4 %.
// The probes along the fit's weakest motions: this many motions, each taken these many cells
// either way (a slid prismatic view is found from within a cell or so of where it belongs).
constexpr int kProbedMotions = 2;
constexpr double kProbeCells[] = {2.0, 4.0};
// And along the weakest motion alone, these shares of L (the points' RMS displacement) either
// way: a partial view of a cast pipe elbow at 2 % noise, turned 40° along its bend, explained 99 %
// of the view (the truth 99.5 %), and ICP from every start within a few cells stayed in that
// valley; from 0.15-0.3 L it reached the truth (docs/registration.md, "Parts never seen").
constexpr double kFarProbeReaches[] = {0.1, 0.2, 0.3};
// ... and refined with this many times the retries' cut-off (4 cells instead of 2.5): a probe
// lands 10-15° from the truth along the bend, where most cells lie farther from their surface
// than 2.5 cells, and a view of the same elbow at 0.5 % noise stayed 38° along it
// (docs/registration.md, "Far probes pair farther").
constexpr double kFarProbeCutoffScale = 1.6;
// Rounds of the retries: a retried pose that the scan sides with but that still leaves some of
// it off the CAD is retried in turn, as its turns and probes are not the first pose's. An
// L-block seen edge-on (0.1 % noise): the first pose put 0.29 of the view's surface on the
// CAD, the retry a leg-for-leg turn 0.81, and the truth, 0.998, is a quarter turn of that one.
constexpr int kRetryRounds = 2;
// Retried poses apart from the pose whose weakest motions are probed in turn.
constexpr std::size_t kProbedRivals = 3;
// How far the centroids must lean the best pose's way before the fitted cells may dismiss a
// rival (registerScan): standard deviations of a coin toss between the two.
constexpr double kLeanSigmas = 2.0;
// ... and by at least this share of the cells, as scanPrefers() asks: a camera view of a
// prismatic bar on a table (the ABC block at 0.5 % noise), turned end for end, leaned its way by
// 14 cells of 1,500 against none, stray cells rather than a feature, and its fitted cells then
// dismissed the truth (docs/benchmarks.md, session 31).
constexpr double kLeanShare = 0.01;

// The second search (registerWidening), after a first with fewer than min_features features,
// accepts features whose r_max ball covers this share of the first search's min_ball_area: a
// holed or narrow view has few whole balls (the dragon's view 72 against view 48: 4 features,
// no congruent triplet; with cut balls 18 and registered).
constexpr double kRetryBallShare = 0.5;

// The pose is fitted to the curve a coarse CAD's faces stand for (chord_error.h) when the
// residuals of the pose fitted to the faces show at least this share of the curve's bulges,
// this many standard errors from none (curveShareAt(): 0.28-0.33 for a pump cover's views
// scanned from its finer mesh, 0 ± 0.05 for scans made from the mesh itself at 0.1 % noise),
// and ICP, fitting the share with the pose, then finds at least the second share, as far from
// none (0.89-0.93 for those views; docs/registration.md, "A coarse CAD").
constexpr double kCurveShareSeen = 0.2;
constexpr double kCurveShareFitted = 0.5;
constexpr double kCurveShareSigmas = 5.0;
// ... read and fitted with the pose on this many points: one number more needs no more (on all
// 20,000 the reading cost the README's sample run 13 ms).
constexpr std::size_t kCurveSharePoints = 5000;
// A share above this is no curve's: two camera views made from the CAD mesh itself, their
// faces' fit 1.5 and 3.5 mm off (edges, mixed pixels), read 7.7 and 1.55 at the faces' pose.
constexpr double kCurveShareMax = 1.5;
// ... and the curve must explain the scan better than the faces: the residuals' robust σ at
// most this share of the faces'. Scans of finer meshes: 0.43-0.90 (pump cover, elbow; the
// blade, whose chord errors sit at its platform's ends, 0.96-0.98 and left on its faces); a
// camera view of the forearm made from its mesh, whose fit had found a share of 0.8: 0.97.
constexpr double kCurveSigmaGain = 0.9;

// A rival that refinement brings within the separation of distinct poses of the best is the
// best's own (an alternative no more) when it also closed at least this share of its gap to it
// (registerScan; in the table at 2 % noise and the pump cover's views the rivals so merged had
// closed 68-96 % of theirs and landed within 0.4 of the separation, the rivals kept at most 20 %,
// staying 1.6 or more apart).
constexpr double kBasinShare = 0.5;

// A refined candidate pose and how much of the scan it explains.
struct RefinedPose {
  Eigen::Isometry3d T_cad_scan;
  double score = 0.0;
};

// A short ICP on the verification cells and the score after it: a coarse fit a few degrees off
// scores low until refined, and a flip that survived verification stays low. ICP's first cut-off
// is `cutoff_scale` times the score's truncation; the score keeps the truncation, so that the
// scores of all starts compare.
RefinedPose refineQuickly(const Model& model,
                          const Eigen::Isometry3d& pose,
                          const VerificationSet& set,
                          const PipelineConfig& config,
                          bool facing,
                          double cutoff_scale) {
  const double truncation = config.registration.verification_distance_cells * model.cellSize();
  IcpConfig quick = config.icp;
  quick.max_iterations = std::min(quick.max_iterations, 15);
  // `facing`: pairs with faces turned the points' way where the normals point out of the
  // material, as in the full refinement (on a wall thinner than the noise the nearest face is
  // often the far side's). Only the retries ask for it: in the hypotheses' ranking it moved the
  // first pose of camera views of a bar (docs/registration.md, "Turns placed by the features").
  const IcpResult icp = refinePose(model.query(),
                                   set.points,
                                   pose,
                                   cutoff_scale * truncation,
                                   model.bounds().diagonal(),
                                   quick,
                                   (facing && set.oriented) ? set.normals : Points());
  const Eigen::Isometry3d refined = icp.usable() ? icp.T_cad_scan : pose;
  return {refined,
          verificationScore(
              refined, set, model.query(), truncation, config.registration.normal_tolerance_deg)};
}

// refineQuickly() for many starts: one parallel region over the poses (the inner batch queries
// then run single-threaded), results in input order whatever the thread count.
std::vector<RefinedPose> refineAll(const Model& model,
                                   const std::vector<Eigen::Isometry3d>& starts,
                                   const VerificationSet& set,
                                   const PipelineConfig& config,
                                   bool facing = false,
                                   double cutoff_scale = 1.0) {
  std::vector<RefinedPose> refined(starts.size());
  const auto count = static_cast<long>(starts.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (long i = 0; i < count; ++i) {
    const auto u = static_cast<std::size_t>(i);
    refined[u] = refineQuickly(model, starts[u], set, config, facing, cutoff_scale);
  }
  return refined;
}

// Three times the spread of `set` about the CAD at `pose`, the median distance read as a
// Gaussian's (/ 0.6745), within [0.25 cell, limit]; 0 when half the points lie farther than
// `limit`. Serial, like verificationTerms().
double spreadBand(const VerificationSet& set,
                  const Eigen::Isometry3d& pose,
                  const MeshQuery& cad,
                  double cell,
                  double limit) {
  std::vector<double> distances;
  distances.reserve(set.points.size());
  for (const Eigen::Vector3d& point : set.points) {
    const ClosestPoint closest = cad.closest(pose * point, limit);
    distances.push_back(closest.found ? closest.distance : std::numeric_limits<double>::infinity());
  }
  if (distances.empty()) {
    return 0.0;
  }
  const double middle = internal::median(std::move(distances));
  if (!std::isfinite(middle)) {
    return 0.0;
  }
  return std::clamp(3.0 * middle / 0.6745, 0.25 * cell, limit);
}

// The symmetric twins S·T and S⁻¹·T of `pose` (symmetry.h), refined.
std::vector<RefinedPose> refinedTwins(const Model& model,
                                      const Eigen::Isometry3d& pose,
                                      const VerificationSet& set,
                                      const PipelineConfig& config) {
  std::vector<Eigen::Isometry3d> twins;
  for (const Symmetry& symmetry : model.symmetries()) {
    twins.push_back(symmetry.S * pose);
    twins.push_back(symmetry.S.inverse() * pose);
  }
  return refineAll(model, twins, set, config);
}

// The best verified hypotheses, refined, then the twins of the best, so a symmetric part cannot
// be reported with one of its twins unseen. `twinned` is the pose whose twins were added.
struct RefinedHypotheses {
  std::vector<RefinedPose> poses;  // best score first
  Eigen::Isometry3d twinned = Eigen::Isometry3d::Identity();
};

RefinedHypotheses refineHypotheses(const Model& model,
                                   const std::vector<PoseHypothesis>& hypotheses,
                                   const VerificationSet& set,
                                   const PipelineConfig& config) {
  const auto count = std::min<std::size_t>(
      hypotheses.size(), static_cast<std::size_t>(config.registration.refined_hypotheses));
  std::vector<Eigen::Isometry3d> starts;
  for (std::size_t h = 0; h < count; ++h) {
    starts.push_back(hypotheses[h].T_cad_scan);
  }
  RefinedHypotheses out;
  out.poses = refineAll(model, starts, set, config);
  const auto by_score = [](const RefinedPose& a, const RefinedPose& b) {
    return a.score > b.score;
  };
  std::stable_sort(out.poses.begin(), out.poses.end(), by_score);
  out.twinned = out.poses.front().T_cad_scan;
  for (const RefinedPose& twin : refinedTwins(model, out.twinned, set, config)) {
    out.poses.push_back(twin);
  }
  std::stable_sort(out.poses.begin(), out.poses.end(), by_score);
  return out;
}

// The starts a pose that leaves some of the scan off the CAD is retried from (registerScan):
// probes along the two motions the fit constrains least, two and four cells either way. A
// prismatic view slides along its axis without leaving the surface, so ICP stays where the
// triplet put it. Far along the weakest motion too: ICP from within four cells returns to where
// the triplet put the pose, and a view of a bend can lie tens of degrees along it.
struct ProbeStarts {
  std::vector<Eigen::Isometry3d> near;
  std::vector<Eigen::Isometry3d> far;  // refined with a wider cut-off (kFarProbeCutoffScale)
};

ProbeStarts probeStarts(const Model& model,
                        const VerificationSet& set,
                        const Eigen::Isometry3d& pose,
                        double truncation) {
  ProbeStarts starts;
  const std::vector<WeakMotion> motions =
      weakestMotions(model.query(), set.points, pose, truncation, kProbedMotions);
  for (const WeakMotion& motion : motions) {
    for (const double cells : kProbeCells) {
      for (const double sign : {-1.0, 1.0}) {
        starts.near.push_back(motion.by(sign * cells * model.cellSize()) * pose);
      }
    }
  }
  if (!motions.empty()) {
    for (const double reach : kFarProbeReaches) {
      for (const double sign : {-1.0, 1.0}) {
        starts.far.push_back(motions.front().by(sign * reach * model.bounds().diagonal()) * pose);
      }
    }
  }
  return starts;
}

// The cube's turns of `pose` about the CAD's principal axes (a bar's view turned about a diagonal
// of its section), about the view's own (the view of a bent sheet that shows its bend is
// symmetric about the bend's bisector, which the part as a whole, with legs of unequal length, is
// not) and about the axes of either one's normals (a sheet part's wall directions, which unequal
// flanges or legs do not tilt as they tilt the axes of its spread).
std::vector<Eigen::Isometry3d> turnStarts(const Model& model,
                                          const SurfaceGraph& scan,
                                          const Eigen::Isometry3d& pose) {
  std::vector<Eigen::Isometry3d> starts;
  for (const Eigen::Isometry3d& turn : principalFrameTurns(model.descriptors().graph)) {
    starts.push_back(turn * pose);
  }
  for (const Eigen::Isometry3d& turn : principalFrameTurns(scan)) {
    starts.push_back(pose * turn);
  }
  for (const Eigen::Isometry3d& turn : model.normalFrameTurns()) {
    starts.push_back(turn * pose);
  }
  for (const Eigen::Isometry3d& turn : normalFrameTurns(scan)) {
    starts.push_back(pose * turn);
  }
  return starts;
}

// The probes of probeStarts() again, about the best few retried poses that are not the pose
// itself: a turned start lands within a few cells of a confusion, and on a sheet part ICP cannot
// close that gap where the walls it should meet are farther than its cut-off (a hat channel
// turned about an axis its unequal flanges move off the centroid).
ProbeStarts probesAroundRivals(const Model& model,
                               const VerificationSet& set,
                               const std::vector<RefinedPose>& retried,
                               const Eigen::Isometry3d& pose,
                               const Eigen::Vector3d& reference,
                               double truncation) {
  std::vector<const RefinedPose*> rivals;
  for (const RefinedPose& candidate : retried) {
    if (candidate.score > 0.0 &&
        separatePoses(pose, candidate.T_cad_scan, reference, model.cellSize()) &&
        std::all_of(rivals.begin(), rivals.end(), [&](const RefinedPose* r) {
          return separatePoses(r->T_cad_scan, candidate.T_cad_scan, reference, model.cellSize());
        })) {
      rivals.push_back(&candidate);
    }
  }
  std::stable_sort(rivals.begin(), rivals.end(), [](const RefinedPose* a, const RefinedPose* b) {
    return a->score > b->score;
  });
  rivals.resize(std::min<std::size_t>(rivals.size(), kProbedRivals));
  ProbeStarts starts;
  for (const RefinedPose* rival : rivals) {
    const ProbeStarts probes = probeStarts(model, set, rival->T_cad_scan, truncation);
    starts.near.insert(starts.near.end(), probes.near.begin(), probes.near.end());
    starts.far.insert(starts.far.end(), probes.far.begin(), probes.far.end());
  }
  return starts;
}

// ICP of the scan from `initial`: on the fitted surfaces' points when the curvature fit grew
// (`surface_points` not empty; the fit's numbers are then measured on the scan's own points),
// each point paired with faces turned its way where `point_normals` are given.
IcpResult refineOnScan(const Model& model,
                       const Points& scan_points,
                       const Points& surface_points,
                       const Points& point_normals,
                       const Eigen::Isometry3d& initial,
                       double initial_cutoff,
                       const IcpConfig& config,
                       const CurvedSurface& curved) {
  const bool on_surfaces = !surface_points.empty();
  const double diagonal = model.bounds().diagonal();
  IcpResult refined = refinePose(model.query(),
                                 on_surfaces ? surface_points : scan_points,
                                 initial,
                                 initial_cutoff,
                                 diagonal,
                                 config,
                                 point_normals,
                                 curved);
  if (on_surfaces && refined.usable()) {
    const IcpResult measured = measureFit(
        model.query(), scan_points, refined.T_cad_scan, diagonal, config, point_normals, curved);
    refined.sigma = measured.sigma;
    refined.inlier_distance = measured.inlier_distance;
    refined.rmse = measured.rmse;
    refined.fitness = measured.fitness;
  }
  return refined;
}

// Takes the refined pose into the result and checks that it explains the scan: the verification
// cells within 3 σ of the residual, ICP's fitness, the share of the scan's surface on the CAD, a
// residual not stretched far past the scan's own noise. False, with status kRegistrationFailed
// and the identity pose (the rejected fit's numbers kept for the message), when it does not.
bool acceptPose(const Model& model,
                const VerificationSet& set,
                const IcpResult& icp,
                double surface_share,
                double coarse_truncation,
                const CurvedSurface& curved,
                const PipelineConfig& config,
                InspectionResult* result) {
  const double diagonal = model.bounds().diagonal();
  if (!icp.converged) {
    result->warnings.push_back(icp.status.message);
  }
  result->T_cad_scan = icp.T_cad_scan;
  result->rmse = icp.rmse;
  result->fitness = icp.fitness;
  result->inlier_distance = icp.inlier_distance;
  result->noise_sigma = icp.sigma;
  result->cad_curve_share = curved.share;
  // The share of the scan the pose explains, at a distance that allows for the measured noise.
  const double explained_within =
      std::clamp(config.icp.sigma_multiple * icp.sigma,
                 coarse_truncation,
                 std::max(coarse_truncation, config.icp.max_cutoff_ratio * diagonal));
  result->score = verificationScore(icp.T_cad_scan,
                                    set,
                                    model.query(),
                                    explained_within,
                                    config.registration.normal_tolerance_deg);
  result->surface_on_cad = surface_share;
  const double noise_floor = std::max(result->scan_noise, 1e-3 * diagonal);
  const bool stretched = icp.sigma > config.registration.max_residual_ratio * noise_floor &&
                         icp.fitness < config.registration.residual_fitness;
  if (result->score >= config.registration.min_score &&
      result->fitness >= config.registration.min_fitness && !stretched &&
      result->surface_on_cad >= config.registration.min_surface_on_cad) {
    return true;
  }
  result->status = Status::failure(
      StatusCode::kRegistrationFailed,
      "no pose explains the scan: best pose explains " + std::to_string(result->score) +
          " of it (registration.min_score " + std::to_string(config.registration.min_score) +
          "), ICP fitness " + std::to_string(result->fitness) + " (registration.min_fitness " +
          std::to_string(config.registration.min_fitness) + "), " +
          std::to_string(result->surface_on_cad) +
          " of the scan's surface on the CAD (registration.min_surface_on_cad " +
          std::to_string(config.registration.min_surface_on_cad) + "), residual " +
          formatLength(icp.sigma) + " for a scan noise of " + formatLength(result->scan_noise) +
          " (registration.max_residual_ratio " +
          std::to_string(config.registration.max_residual_ratio) + ")");
  result->T_cad_scan = Eigen::Isometry3d::Identity();
  result->rmse = std::numeric_limits<double>::quiet_NaN();
  return false;
}

// Features → candidates → triplets → verification → ICP. Fills the registration fields of
// `result`; the status says why when no pose could be trusted.
// `oriented`: the scan's normals point out of the material (see VerificationSet).
void registerScan(const Model& model,
                  const Points& scan_points,
                  const DescriptorResult& scan,
                  bool oriented,
                  const PipelineConfig& config,
                  const ProgressCallback& progress,
                  InspectionResult* result) {
  Stopwatch watch{result, &progress};
  if (!watch.proceed("features", 0.45)) {
    return;
  }
  const DescriptorResult& cad = model.descriptors();
  const double r_max = cad.radii.back();
  const double cell = model.cellSize();
  // A cell whose largest ball is cut by the edge of a partial scan has descriptors the CAD does
  // not share there: it cannot be a feature.
  GeodesicBallGrower grower(scan.graph);
  double ball_share = config.features.min_ball_area;
  const auto whole_ball = [&](int cell) {
    double area = 0.0;
    for (const BallMember& member : grower.grow(cell, r_max)) {
      area += scan.graph.area[static_cast<std::size_t>(member.cell)];
    }
    return area >= ball_share * kPi * r_max * r_max;
  };
  FeatureResult features =
      selectFeatures(scan.graph.centroids, scan.cell_values, r_max, config.features, whole_ball);
  // A narrow view (a blade seen edge-on) has few whole balls: accept balls cut down to half
  // rather than give up, when that is what stands between the scan and a triplet.
  if (static_cast<int>(features.cells.size()) < config.features.min_features) {
    ball_share = 0.5 * config.features.min_ball_area;
    FeatureResult relaxed =
        selectFeatures(scan.graph.centroids, scan.cell_values, r_max, config.features, whole_ball);
    if (relaxed.cells.size() > features.cells.size()) {
      features = std::move(relaxed);
    }
  }
  watch.lap("features");
  result->counts.features = features.cells.size();
  if (!features.status.ok()) {
    result->status = features.status;
    return;
  }
  if (!watch.proceed("correspondences", 0.47)) {
    return;
  }
  // A cloud without normals that visibility could not orient (a single view) took its normals'
  // sign from a centroid vote, which turns a concave view inside out (the pressure side of a
  // blade seen alone): its curvature changes sign and every V_k reads 1 − V_k. Such a scan is
  // also matched with its descriptors mirrored, and verification, blind to the normals' sign
  // for it, chooses between the poses of both.
  std::vector<CorrespondenceResult> candidates;
  candidates.push_back(findCandidates(scan.cell_values,
                                      features.cells,
                                      cad.cell_values,
                                      cad.graph.centroids,
                                      cell,
                                      config.correspondence));
  if (!oriented && scan.curvature.signs_guessed) {
    const Eigen::MatrixXd mirrored = (1.0 - scan.cell_values.array()).matrix();
    candidates.push_back(findCandidates(mirrored,
                                        features.cells,
                                        cad.cell_values,
                                        cad.graph.centroids,
                                        cell,
                                        config.correspondence));
  }
  watch.lap("correspondences");
  result->counts.candidates = candidates.front().candidates;
  if (!candidates.front().status.ok()) {
    result->status = candidates.front().status;
    return;
  }
  if (!watch.proceed("global_registration", 0.5)) {
    return;
  }
  // Both signs' hypotheses in one list, best verified first.
  std::vector<PoseHypothesis> hypotheses;
  std::vector<Status> failures;
  for (const CorrespondenceResult& sign : candidates) {
    GlobalRegistrationResult one = registerGlobally(
        scan.graph, cad.graph, sign, model.query(), cell, r_max, config.registration, oriented);
    if (!one.status.ok()) {
      failures.push_back(one.status);
    }
    hypotheses.insert(hypotheses.end(), one.hypotheses.begin(), one.hypotheses.end());
  }
  std::stable_sort(
      hypotheses.begin(), hypotheses.end(), [](const PoseHypothesis& a, const PoseHypothesis& b) {
        return a.score > b.score;
      });
  if (hypotheses.empty()) {
    watch.lap("global_registration");
    result->status = failures.front();
    return;
  }
  const VerificationSet set =
      makeVerificationSet(scan.graph, config.registration.verification_points, oriented);
  const RefinedHypotheses hypotheses_refined = refineHypotheses(model, hypotheses, set, config);
  const std::vector<RefinedPose>& refined = hypotheses_refined.poses;
  watch.lap("global_registration");
  if (!watch.proceed("icp", 0.75)) {
    return;
  }

  const double coarse_truncation = config.registration.verification_distance_cells * cell;
  const double diagonal = model.bounds().diagonal();
  const Eigen::Vector3d reference = set.centroid();
  // Contenders: distinct refined poses close to the best by the coarse score.
  std::vector<RefinedPose> contenders;
  for (const RefinedPose& pose : refined) {
    const bool apart = std::all_of(contenders.begin(), contenders.end(), [&](const RefinedPose& c) {
      return separatePoses(c.T_cad_scan, pose.T_cad_scan, reference, cell);
    });
    if (apart && pose.score >= 0.8 * refined.front().score) {
      contenders.push_back(pose);
    }
  }
  // On a noisy cloud the curvature fit grew (descriptor.h): the quadrics fitted to its
  // neighbourhoods carry the surface with the noise averaged out. ICP on them is not drawn by
  // closest points that the noise pushed onto other faces (from the true pose, a tube turned
  // 2-6° about its axis at 2 % noise, 0.5-1° on planes), nor by the planes' cut through every
  // bend (blade partial views at 2 %: 1.49° on planes, 1.15° on quadrics). The fit's numbers
  // stay those of the measured points. Empty, so ICP takes the measured points, unless the fit
  // grew.
  const Points surface_points = scan.onFittedSurfaces(scan_points);
  const bool on_surfaces = !surface_points.empty();
  // Normals that point out of the material pair each point with a face turned its way: on a
  // wall thinner than the noise, the nearest face is often the far side (a bent 2 mm sheet at
  // σ = 1.8 mm: every pose 1 % of L into the sheet, some views turned by 1-2°).
  const Points point_normals = oriented ? scan.pointNormals(scan_points.size()) : Points();
  // The faces of the CAD (no curve, so ICP reads no bulges), until the scan shows that it
  // follows the curve they stand for.
  CurvedSurface curved;
  const auto refine = [&](const Eigen::Isometry3d& initial) {
    return refineOnScan(model,
                        scan_points,
                        surface_points,
                        point_normals,
                        initial,
                        coarse_truncation,
                        config.icp,
                        curved);
  };
  IcpResult icp = refine(contenders.front().T_cad_scan);
  // The contenders are ranked again with a truncation matched to the measured residual (3σ):
  // near-symmetric twins that the coarse truncation scores alike separate here.
  const double fine =
      std::clamp(config.icp.sigma_multiple * icp.sigma, 0.25 * cell, coarse_truncation);
  const auto fineScore = [&](const Eigen::Isometry3d& pose) {
    return verificationScore(
        pose, set, model.query(), fine, config.registration.normal_tolerance_deg);
  };
  std::vector<double> fine_scores;
  std::size_t best = 0;
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    fine_scores.push_back(fineScore(c == 0 ? icp.T_cad_scan : contenders[c].T_cad_scan));
    if (fine_scores[c] > fine_scores[best]) {
      best = c;
    }
  }
  if (best != 0) {
    icp = refine(contenders[best].T_cad_scan);
    fine_scores[best] = std::max(fine_scores[best], fineScore(icp.T_cad_scan));
  }
  // A scan of a real part lies on the curve a coarse CAD's faces stand for, outside them where
  // the part is convex: fitted to the faces, the pose moves to split the difference (a pump
  // cover at 16 facets per circle, 1.1 mm chords: 1.7-1.9° off at 0.1 % noise). Where the scan
  // shows it, the pose is fitted to the curve (chord_error.h). Not on quadric points: they are
  // a smooth surface whatever the CAD (scans of the mesh itself read 0.4 of the curve there).
  if (icp.usable() && !on_surfaces) {
    IcpConfig share_config = config.icp;
    share_config.max_points = std::min(share_config.max_points, kCurveSharePoints);
    const CurveShare seen = curveShareAt(model.query(),
                                         model.chordError(),
                                         scan_points,
                                         icp.T_cad_scan,
                                         icp.inlier_distance,
                                         share_config,
                                         point_normals);
    if (seen.share >= kCurveShareSeen && seen.share >= kCurveShareSigmas * seen.error) {
      CurvedSurface free;
      free.chord = &model.chordError();
      free.estimate = true;
      const IcpResult joint = refinePose(model.query(),
                                         scan_points,
                                         icp.T_cad_scan,
                                         icp.inlier_distance,
                                         diagonal,
                                         share_config,
                                         point_normals,
                                         free);
      if (joint.usable() && joint.curve_share >= kCurveShareFitted &&
          joint.curve_share <= kCurveShareMax &&
          joint.curve_share >= kCurveShareSigmas * joint.curve_share_error) {
        curved.chord = &model.chordError();
        curved.share = std::min(joint.curve_share, 1.0);
        const IcpResult on_curve = refine(joint.T_cad_scan);
        if (on_curve.usable() && on_curve.sigma <= kCurveSigmaGain * icp.sigma) {
          icp = on_curve;
        } else {
          curved = CurvedSurface();
        }
      }
    }
  }
  // The verification terms of a pose: which cells it explains within 3 σ of the scan's noise.
  const double evidence =
      std::clamp(config.icp.sigma_multiple * result->scan_noise, 0.25 * cell, coarse_truncation);
  const auto termsAt = [&](const Eigen::Isometry3d& pose) {
    return verificationTerms(
        pose, set, model.query(), evidence, config.registration.normal_tolerance_deg);
  };
  // The share of the scan's surface the fit puts on the CAD, once per fit: it decides the retry
  // below and is reported as surface_on_cad.
  const auto surfaceShare = [&](const IcpResult& fit) {
    return surfaceOnCad(scan.graph,
                        scan_points,
                        model.query(),
                        fit.T_cad_scan,
                        fit.inlier_distance,
                        config.registration.verification_points,
                        /*min_links=*/3,
                        curved);
  };
  double surface_share = icp.usable() ? surfaceShare(icp) : 0.0;
  // A pose that leaves some of the scan's surface off the CAD may be a confusion that neither the
  // triplets nor the twins reached: a bar's view turned about a diagonal of its section, a bent
  // sheet's view with its legs swapped, a prismatic view slid along its axis. It is retried from
  // the probes along its weakest motions, the turns that the features' translation votes place
  // (votedTurnStarts: a turn about the centroid is many cells off where a part's mass is off its
  // near-symmetry's axis), below kRetryBelowSurface every turn as it is, then the probes about
  // the best few poses so found (probesAroundRivals); above it the half turns about the CAD's
  // walls. A retried pose the scan clearly sides with (scanPrefers), still after it is refined as
  // fully as the pose, replaces it; one the scan cannot tell from it becomes a contender, so that
  // the verification below says ambiguous instead of picking one.
  for (int round = 0; round < kRetryRounds && icp.usable() && surface_share < kProbeBelowSurface;
       ++round) {
    const ProbeStarts probes = probeStarts(model, set, icp.T_cad_scan, coarse_truncation);
    std::vector<Eigen::Isometry3d> starts = probes.near;
    const bool turn = surface_share < kRetryBelowSurface;
    if (turn) {
      const std::vector<Eigen::Isometry3d> turned = turnStarts(model, scan.graph, icp.T_cad_scan);
      const std::vector<Eigen::Isometry3d> voted =
          internal::votedTurnStarts(turned, candidates, scan.graph, cad.graph, reference, cell);
      starts.insert(starts.end(), turned.begin(), turned.end());
      starts.insert(starts.end(), voted.begin(), voted.end());
      const std::vector<Eigen::Isometry3d> placed = internal::surfaceVotedTurnStarts(
          turned, scan.graph, cad.graph, oriented, reference, cell);
      starts.insert(starts.end(), placed.begin(), placed.end());
    }
    std::vector<RefinedPose> retried = refineAll(model, starts, set, config, turn);
    const std::vector<RefinedPose> far =
        refineAll(model, probes.far, set, config, turn, kFarProbeCutoffScale);
    retried.insert(retried.end(), far.begin(), far.end());
    if (turn) {
      const ProbeStarts around =
          probesAroundRivals(model, set, retried, icp.T_cad_scan, reference, coarse_truncation);
      for (const auto& [group, scale] :
           {std::pair{&around.near, 1.0}, std::pair{&around.far, kFarProbeCutoffScale}}) {
        const std::vector<RefinedPose> probed = refineAll(model, *group, set, config, true, scale);
        retried.insert(retried.end(), probed.begin(), probed.end());
      }
    } else {
      std::vector<Eigen::Isometry3d> wall_turns;
      for (const Eigen::Isometry3d& wall_turn : model.normalFrameTurns()) {
        if (Eigen::AngleAxisd(wall_turn.linear()).angle() > 0.9 * kPi) {  // 9 half turns a frame
          wall_turns.push_back(wall_turn * icp.T_cad_scan);
        }
      }
      // Turned starts pair with faces turned the points' way, as the turns below 0.95 do.
      const std::vector<RefinedPose> turned = refineAll(model, wall_turns, set, config, true);
      retried.insert(retried.end(), turned.begin(), turned.end());
    }
    const std::vector<double> current_terms = termsAt(icp.T_cad_scan);
    const double current_score = fineScore(icp.T_cad_scan);
    const RefinedPose* chosen = nullptr;
    double chosen_score = 0.0;
    for (const RefinedPose& pose : retried) {
      const double score = fineScore(pose.T_cad_scan);
      if (scanPrefers(termsAt(pose.T_cad_scan), current_terms)) {
        if (chosen == nullptr || score > chosen_score) {
          chosen = &pose;
          chosen_score = score;
        }
      } else if (score >= config.registration.ambiguity_ratio * current_score &&
                 separatePoses(icp.T_cad_scan, pose.T_cad_scan, reference, cell) &&
                 std::all_of(contenders.begin(), contenders.end(), [&](const RefinedPose& c) {
                   return separatePoses(c.T_cad_scan, pose.T_cad_scan, reference, cell);
                 })) {
        contenders.push_back(pose);
        fine_scores.push_back(score);
      }
    }
    bool moved_on = false;
    if (chosen != nullptr) {
      const IcpResult moved = refine(chosen->T_cad_scan);
      if (moved.usable() && scanPrefers(termsAt(moved.T_cad_scan), current_terms)) {
        icp = moved;
        surface_share = surfaceShare(icp);
        contenders.push_back(*chosen);
        fine_scores.push_back(std::max(chosen_score, fineScore(icp.T_cad_scan)));
        best = contenders.size() - 1;
        moved_on = true;
      }
    }
    if (!moved_on) {
      break;  // the pose stands: a second round would search from the same place
    }
  }
  // Then: does the pose explain the scan, and does no other pose explain it as well? For a part
  // with many near-twins (a flange with bolt holes) the scan may side against every rival, and
  // each is then refined to convergence: up to a second, so it is a stage of its own.
  if (!watch.icpDone(icp)) {
    return;
  }
  std::size_t explained = 0;
  for (const CorrespondenceResult& sign : candidates) {
    explained = std::max(explained,
                         static_cast<std::size_t>(countExplainedFeatures(
                             icp.T_cad_scan,
                             scan.graph,
                             cad.graph,
                             sign,
                             config.registration.pair_tolerance_cells * cell)));
  }
  result->counts.correspondences = explained;
  if (!acceptPose(model, set, icp, surface_share, coarse_truncation, curved, config, result)) {
    watch.lap("verification");
    return;
  }
  // The ranking may have put a twin of the quick ranking's best first, and that twin's own twins
  // were never tried: one of them may explain the scan as well (a bar seen from one side, where
  // the winning twin had slid along the bar and the true pose was its half turn).
  // A twin joins the contenders unless the best or a contender that explains at least as much
  // lies near it: the retries' poses about a half turn of a box seen along its length and one
  // end had drifted a cell or two along it (0.83-0.88 of the view explained) and kept out its
  // exact twins (0.964, as the pose itself). The drifted contender stays too: here a rival is
  // only added, never taken away.
  if (separatePoses(hypotheses_refined.twinned, result->T_cad_scan, reference, cell)) {
    for (const RefinedPose& twin : refinedTwins(model, result->T_cad_scan, set, config)) {
      const double twin_score = fineScore(twin.T_cad_scan);
      bool covered = false;
      for (std::size_t c = 0; c < contenders.size() && !covered; ++c) {
        covered = !separatePoses(contenders[c].T_cad_scan, twin.T_cad_scan, reference, cell) &&
                  (c == best || fine_scores[c] >= twin_score);
      }
      if (!covered) {
        fine_scores.push_back(twin_score);
        contenders.push_back(twin);
      }
    }
  }
  // Another distinct pose that explains the scan about as well: say so, with all of them,
  // unless the points the two explain differently side clearly with the best (scanPrefers).
  // A rival the scan sides against is refined as fully as the best before that is believed, so
  // that no edge in refinement decides; and the points are counted within 3 σ of the scan's own
  // noise, not of the best pose's residual: a twin that is only roughly aligned (a camera view of
  // the blade turned by 178°, residual 96 σ) must not explain the scan at its own loose tolerance.
  // A rival is within reach of the best's lower score, quickly refined as the rivals are or
  // fully refined: full refinement alone can lift the best past its twins (a flange's 120° twin:
  // best 0.57 quick, 0.63 full, twin 0.57), or move it off the pose it was ranked at (0.38 quick,
  // 0.37 full, 11° away) — neither may decide that no rival is left.
  const double reach = config.registration.ambiguity_ratio *
                       std::min(fine_scores[best], fineScore(contenders[best].T_cad_scan));
  // On a noisy cloud whose fit grew, a cell's centroid is the mean of a few measured points and
  // keeps most of their noise (a UR10e forearm at 2 % noise: 10 mm off the CAD at the median
  // for σ = 13 mm), and within 3 σ of that a half-turned twin explains nearly all a right pose
  // does: the points only the best explains outnumber the twin's by 1.5 to 1, not the 2 to 1
  // scanPrefers asks. The same cells at their points' mean on the fitted surfaces lie 3.5 mm off
  // at the median, and within 3 of that spread at the best pose the twin is told apart by 4 to 1.
  // That sharper test also counts what refinement left, so it may dismiss a rival only where the
  // centroids lean the best's way too (scanLeans, two standard deviations and 1 % of the cells): a
  // flange seen from one side, turned 7.6° about its axis, beat each of its other turns on the
  // fitted cells, and the centroids side with none of them. A wrong best pose spreads the fitted
  // cells wider, which makes the test more lenient, not less.
  VerificationSet fitted;  // only when a rival needs it
  double fitted_band = 0.0;
  std::vector<double> best_terms;
  std::vector<double> best_fitted_terms;
  const auto fittedTermsAt = [&](const Eigen::Isometry3d& pose) {
    return verificationTerms(
        pose, fitted, model.query(), fitted_band, config.registration.normal_tolerance_deg);
  };
  const auto sidesWithBest = [&](const Eigen::Isometry3d& pose) {
    const std::vector<double> terms = termsAt(pose);
    return scanPrefers(best_terms, terms) ||
           (fitted_band > 0.0 && scanLeans(best_terms, terms, kLeanSigmas, kLeanShare) &&
            scanPrefers(best_fitted_terms, fittedTermsAt(pose)));
  };
  // Contenders may lie near each other (a twin beside a drifted pose): each alternative is
  // reported once.
  const auto addAlternative = [&](const Eigen::Isometry3d& pose) {
    if (std::all_of(result->alternatives.begin(),
                    result->alternatives.end(),
                    [&](const Eigen::Isometry3d& other) {
                      return separatePoses(other, pose, reference, cell);
                    })) {
      result->alternatives.push_back(pose);
    }
  };
  // The rivals within reach, each refined to convergence on the verification cells, the points
  // its evidence is counted on (at their fitted places when the fit grew: the best was refined
  // on the fitted points too), in one parallel region: on the whole scan (up to 20,000 points)
  // each rival took 0.5-1 s, and a flange's eleven twins 11 s.
  std::vector<std::size_t> rivals;
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    if (c != best && fine_scores[c] >= reach &&
        separatePoses(result->T_cad_scan, contenders[c].T_cad_scan, reference, cell)) {
      rivals.push_back(c);
    }
  }
  if (!rivals.empty()) {
    best_terms = termsAt(result->T_cad_scan);
    if (on_surfaces) {
      fitted = makeVerificationSet(
          scan.graph, config.registration.verification_points, oriented, surface_points);
      fitted_band = spreadBand(fitted, result->T_cad_scan, model.query(), cell, coarse_truncation);
      if (fitted_band > 0.0) {
        best_fitted_terms = fittedTermsAt(result->T_cad_scan);
      }
    }
  }
  std::vector<IcpResult> settled(rivals.size());
  const auto rival_count = static_cast<long>(rivals.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (long r = 0; r < rival_count; ++r) {
    settled[static_cast<std::size_t>(r)] =
        refinePose(model.query(),
                   fitted_band > 0.0 ? fitted.points : set.points,
                   contenders[rivals[static_cast<std::size_t>(r)]].T_cad_scan,
                   coarse_truncation,
                   diagonal,
                   config.icp);
  }
  for (std::size_t r = 0; r < rivals.size(); ++r) {
    const RefinedPose& found = contenders[rivals[r]];
    const IcpResult& rival = settled[r];
    // Refinement may bring the rival onto the best pose: then both lie in one basin, and the
    // quick refinement had only stopped partway along a motion the view fixes weakly (a UR10e
    // forearm at 2 % noise, its full views' rivals 10-13° about the tube's axis: refined, they
    // land within 0.9-2.6° of the best; docs/registration.md, "Rivals in the best pose's basin").
    // Onto the best means within the separation of distinct poses, and at least halfway there
    // from where the rival started: one found just beyond 10° that refinement barely moved has
    // not shown that it belongs to the best.
    const bool onto_best =
        rival.usable() &&
        refinedOnto(
            result->T_cad_scan, found.T_cad_scan, rival.T_cad_scan, reference, cell, kBasinShare);
    // First the rival as the quick refinement on the verification cells left it. If the scan
    // does not side with the best even then, refining it to convergence, which lets the rival
    // explain more, would not change that: it stays a rival, unless it was the best's.
    if (!sidesWithBest(found.T_cad_scan)) {
      if (!onto_best) {
        addAlternative(found.T_cad_scan);
      }
      continue;
    }
    // The scan sides against the rival as found; it stays beaten unless its refinement, landing
    // apart from the best, explains the scan as well; brought onto the best, it stays beaten.
    if (rival.usable() && separatePoses(result->T_cad_scan, rival.T_cad_scan, reference, cell) &&
        !sidesWithBest(rival.T_cad_scan)) {
      addAlternative(rival.T_cad_scan);
    }
  }
  // How near the best distinct rival comes, on the scores matched to the measured residual.
  double rival_score = 0.0;
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    if (c != best && separatePoses(result->T_cad_scan, contenders[c].T_cad_scan, reference, cell)) {
      rival_score = std::max(rival_score, fine_scores[c]);
    }
  }
  result->ambiguity =
      fine_scores[best] > 0.0 ? std::min(1.0, rival_score / fine_scores[best]) : 0.0;
  watch.lap("verification");
  if (!result->alternatives.empty()) {
    result->registration = RegistrationStatus::kAmbiguous;
    result->status = Status::failure(
        StatusCode::kAmbiguous,
        std::to_string(result->alternatives.size() + 1) +
            " distinct poses explain the scan about equally well (the part looks symmetric from "
            "this view): the best is reported, the others are in alternatives");
    return;
  }
  result->registration = RegistrationStatus::kOk;
  result->status = Status::success();
  result->status.message = "registered: " + std::to_string(result->counts.correspondences) +
                           " feature correspondences, RMS " + formatLength(result->rmse) +
                           ", fitness " + std::to_string(result->fitness);
}

// Stage times of a second attempt added to those of the first, stage by stage.
void addTimings(const std::vector<StageTiming>& extra, std::vector<StageTiming>* timings) {
  for (const StageTiming& timing : extra) {
    const auto same = std::find_if(timings->begin(), timings->end(), [&](const StageTiming& t) {
      return t.stage == timing.stage;
    });
    if (same == timings->end()) {
      timings->push_back(timing);
    } else {
      same->seconds += timing.seconds;
    }
  }
}

// The known-pose path's retry (registerFrom): while `icp`'s pose leaves more than 1 % of the
// scan's surface off the CAD, the probes along its weakest motions (probeStarts), quickly
// refined; the one the scan clearly sides with (scanPrefers), the best scored of such, replaces
// the pose once `refine` has refined it as fully and the scan still sides with it. Probes are
// ranked and compared as the search's retries are: on the verification cells, within 3 σ of the
// fit's residual and of the scan's own noise. `refine` and `surface_share` are registerFrom's.
template <typename Refine, typename SurfaceShare>
void probeAlongWeakMotions(const Model& model,
                           const VerificationSet& set,
                           const PipelineConfig& config,
                           double scan_noise,
                           const Refine& refine,
                           const SurfaceShare& surfaceShare,
                           IcpResult* icp,
                           double* surface_share) {
  const double cell = model.cellSize();
  const double coarse_truncation = config.registration.verification_distance_cells * cell;
  const double fine =
      std::clamp(config.icp.sigma_multiple * icp->sigma, 0.25 * cell, coarse_truncation);
  const double evidence =
      std::clamp(config.icp.sigma_multiple * scan_noise, 0.25 * cell, coarse_truncation);
  const double normal_tolerance = config.registration.normal_tolerance_deg;
  const auto termsAt = [&](const Eigen::Isometry3d& pose) {
    return verificationTerms(pose, set, model.query(), evidence, normal_tolerance);
  };
  for (int round = 0; round < kRetryRounds && *surface_share < kProbeBelowSurface; ++round) {
    const ProbeStarts probes = probeStarts(model, set, icp->T_cad_scan, coarse_truncation);
    // Below kRetryBelowSurface the probes pair with faces turned the points' way, as the
    // search's retries do there.
    const bool facing = *surface_share < kRetryBelowSurface;
    std::vector<RefinedPose> retried = refineAll(model, probes.near, set, config, facing);
    const std::vector<RefinedPose> far =
        refineAll(model, probes.far, set, config, facing, kFarProbeCutoffScale);
    retried.insert(retried.end(), far.begin(), far.end());
    const std::vector<double> current_terms = termsAt(icp->T_cad_scan);
    const RefinedPose* chosen = nullptr;
    double chosen_score = 0.0;
    for (const RefinedPose& pose : retried) {
      if (!scanPrefers(termsAt(pose.T_cad_scan), current_terms)) {
        continue;
      }
      const double score =
          verificationScore(pose.T_cad_scan, set, model.query(), fine, normal_tolerance);
      if (chosen == nullptr || score > chosen_score) {
        chosen = &pose;
        chosen_score = score;
      }
    }
    if (chosen == nullptr) {
      return;
    }
    const IcpResult moved = refine(chosen->T_cad_scan);
    if (!moved.usable() || !scanPrefers(termsAt(moved.T_cad_scan), current_terms)) {
      return;
    }
    *icp = moved;
    *surface_share = surfaceShare(*icp);
  }
}

// The registration of a scan whose pose is known roughly (inspectFrom): ICP from `initial` as
// the global stage's best pose is refined, and the same checks that the pose explains the scan.
// No search, so no rivals: a pose the scan would not tell from a symmetric twin is the caller's.
// A pose that leaves some of the scan's surface off the CAD is probed along its weakest motions,
// as the search probes its best pose, and moves to a probe that the scan clearly sides with: a
// guess 15° and 2 % of L off a flange's view had slid onto a bolt-hole turn 17° off, 0.95 of the
// view on the CAD, and been reported ok.
void registerFrom(const Model& model,
                  const Points& scan_points,
                  const DescriptorResult& scan,
                  bool oriented,
                  const Eigen::Isometry3d& initial,
                  const PipelineConfig& config,
                  const ProgressCallback& progress,
                  InspectionResult* result) {
  Stopwatch watch{result, &progress};
  if (!watch.proceed("icp", 0.75)) {
    return;
  }
  const double cell = model.cellSize();
  const double coarse_truncation = config.registration.verification_distance_cells * cell;
  const Points surface_points = scan.onFittedSurfaces(scan_points);
  const Points point_normals = oriented ? scan.pointNormals(scan_points.size()) : Points();
  const CurvedSurface faces;
  const auto refine = [&](const Eigen::Isometry3d& start) {
    return refineOnScan(model,
                        scan_points,
                        surface_points,
                        point_normals,
                        start,
                        coarse_truncation,
                        config.icp,
                        faces);
  };
  const auto surfaceShare = [&](const IcpResult& fit) {
    return surfaceOnCad(scan.graph,
                        scan_points,
                        model.query(),
                        fit.T_cad_scan,
                        fit.inlier_distance,
                        config.registration.verification_points,
                        /*min_links=*/3,
                        faces);
  };
  IcpResult icp = refine(initial);
  const VerificationSet set =
      makeVerificationSet(scan.graph, config.registration.verification_points, oriented);
  double surface_share = icp.usable() ? surfaceShare(icp) : 0.0;
  const Eigen::Isometry3d reached = icp.T_cad_scan;
  const double reached_share = surface_share;
  if (icp.usable()) {
    probeAlongWeakMotions(
        model, set, config, result->scan_noise, refine, surfaceShare, &icp, &surface_share);
  }
  if (!watch.icpDone(icp)) {
    return;
  }
  if (!acceptPose(model, set, icp, surface_share, coarse_truncation, faces, config, result)) {
    watch.lap("verification");
    return;
  }
  result->registration = RegistrationStatus::kOk;
  result->status = Status::success();
  result->status.message = "refined from the given pose: RMS " + formatLength(result->rmse) +
                           ", fitness " + std::to_string(result->fitness);
  fitToAlignedRegions(model, scan_points, point_normals, config, result);
  watch.lap("verification");
  // How far the part sat from the given pose (a fixture's nominal): the turn, and the shift of
  // the scan's centroid, where the part is.
  const Eigen::Vector3d reference = set.centroid();
  const PoseDifference offset = poseDifference(initial, result->T_cad_scan, reference);
  result->offset_from_initial_deg = offset.angle * 180.0 / kPi;
  result->offset_from_initial = offset.shift;
  if (separatePoses(reached, result->T_cad_scan, reference, cell)) {
    const PoseDifference retried = poseDifference(reached, result->T_cad_scan, reference);
    result->warnings.push_back(
        "ICP from the initial pose left " + std::to_string(1.0 - reached_share) +
        " of the scan's surface off the CAD; a pose " +
        std::to_string(retried.angle * 180.0 / kPi) + " deg and " + formatLength(retried.shift) +
        " from it, found along the fit's weakest motions, explains the scan better and is "
        "reported");
  } else if (separatePoses(initial, result->T_cad_scan, reference, cell)) {
    // A guess that ICP moved as far as poses the search would list apart may have slid onto a
    // near-twin (a flange's bolt-hole turns: from 10-20° off, a quarter of the guesses did).
    result->warnings.push_back(
        "ICP moved the pose " + std::to_string(result->offset_from_initial_deg) + " deg and " +
        formatLength(result->offset_from_initial) +
        " from the initial pose: on a part with near-twins it may have slid onto one; search "
        "without the initial pose to check");
  }
}

// The fixed alignment (inspectAt): the given pose as it is, its fit measured there and gating
// nothing. Where the part lies is measured apart: registerFrom() from the pose into a scratch
// result, for the offset alone, so the deviation stays in the given pose's frame while the report
// says how much of it is the part sitting off that pose.
void registerFixed(const Model& model,
                   const Points& scan_points,
                   const DescriptorResult& scan,
                   bool oriented,
                   const Eigen::Isometry3d& pose,
                   const PipelineConfig& config,
                   const ProgressCallback& progress,
                   InspectionResult* result) {
  InspectionResult refined;
  refined.scan_noise = result->scan_noise;
  registerFrom(model, scan_points, scan, oriented, pose, config, progress, &refined);
  addTimings(refined.timings, &result->timings);
  if (refined.status.code == StatusCode::kCancelled) {
    result->status = refined.status;
    return;
  }
  Stopwatch watch{result, &progress};
  const double diagonal = model.bounds().diagonal();
  const Points point_normals = oriented ? scan.pointNormals(scan_points.size()) : Points();
  const IcpResult fit =
      measureFit(model.query(), scan_points, pose, diagonal, config.icp, point_normals);
  result->T_cad_scan = pose;
  result->fitness = fit.fitness;
  const VerificationSet set =
      makeVerificationSet(scan.graph, config.registration.verification_points, oriented);
  if (fit.status.ok() && fit.fitness > 0.0) {  // else no scan point lies near the CAD there
    result->rmse = fit.rmse;
    result->inlier_distance = fit.inlier_distance;
    result->noise_sigma = fit.sigma;
    result->surface_on_cad = surfaceOnCad(scan.graph,
                                          scan_points,
                                          model.query(),
                                          pose,
                                          fit.inlier_distance,
                                          config.registration.verification_points,
                                          /*min_links=*/3,
                                          CurvedSurface());
    result->score = verificationScore(
        pose, set, model.query(), fit.inlier_distance, config.registration.normal_tolerance_deg);
  }
  watch.lap("verification");
  result->registration = RegistrationStatus::kFixed;
  result->status = Status::success();
  result->status.message = "fixed alignment: the given pose, not registered";
  if (refined.registration != RegistrationStatus::kOk) {
    result->warnings.push_back(
        "fixed alignment: no pose near the given one explains the scan, so how far the part sits "
        "from it is not known (" +
        refined.status.message + ")");
    return;
  }
  // registerFrom() measured the offset from `pose`, its initial pose, at the same centroid.
  result->offset_from_initial_deg = refined.offset_from_initial_deg;
  result->offset_from_initial = refined.offset_from_initial;
  // A part that sits off the pose by more than the band shows that as deviation everywhere.
  const double band = std::min(config.tolerance.upper, -config.tolerance.lower);
  if (result->offset_from_initial > band) {
    result->warnings.push_back(
        "fixed alignment: the part sits " + formatLength(result->offset_from_initial) + " and " +
        std::to_string(result->offset_from_initial_deg) +
        " deg from the given pose, more than the tolerance band's " + formatLength(band) +
        ": the deviations measure where it sits as well as its shape");
  }
}

// registerScan(), and when no pose explained the scan, once more with `retry_candidates` per
// feature, and where the features were few, with features whose r_max ball is cut down to half
// the usual share: on a partial or noisy scan a feature's true place can rank below the first
// max_candidates in descriptor space (a partial view's wide scales read flatter than the CAD's
// there), and a narrow or holed view has too few whole balls to give a triplet its three true
// matches. Scans that register at the first attempt are not touched.
void registerWidening(const Model& model,
                      const Points& scan_points,
                      const DescriptorResult& scan,
                      bool oriented,
                      const PipelineConfig& config,
                      const ProgressCallback& progress,
                      InspectionResult* result) {
  const InspectionResult before = *result;
  registerScan(model, scan_points, scan, oriented, config, progress, result);
  const int first = config.correspondence.max_candidates;
  const int wider = config.correspondence.retry_candidates;
  // Too few features for candidates (a narrow view) is worth it too: cut balls may add some.
  const bool few_features =
      result->counts.features < static_cast<std::size_t>(config.features.min_features);
  const bool worth_retrying = result->counts.candidates > 0 || few_features;
  if (result->registration != RegistrationStatus::kFailed ||
      result->status.code != StatusCode::kRegistrationFailed || !worth_retrying || wider <= first) {
    return;
  }
  PipelineConfig widened = config;
  widened.correspondence.max_candidates = wider;
  // Cut balls only where whole ones were too few (the first search relaxed its share once
  // already): with enough features they would only trade good ones for cut ones.
  if (few_features) {
    widened.features.min_ball_area = kRetryBallShare * config.features.min_ball_area;
  }
  const std::string searched =
      "up to " + std::to_string(wider) +
      " CAD candidates per feature (correspondence.retry_candidates)" +
      (few_features ? std::string(" and features whose ball the view cuts") : std::string());
  InspectionResult retry = before;
  retry.timings.clear();
  registerScan(model, scan_points, scan, oriented, widened, progress, &retry);
  if (retry.status.code == StatusCode::kCancelled) {  // the caller stopped the second search
    result->status = retry.status;
  }
  if (retry.registration == RegistrationStatus::kFailed) {
    addTimings(retry.timings, &result->timings);
    result->warnings.push_back("searched again with " + searched + ": no pose either");
    return;
  }
  std::vector<StageTiming> timings = result->timings;
  addTimings(retry.timings, &timings);
  retry.timings = std::move(timings);
  retry.warnings.push_back("registered with " + searched + ": with " + std::to_string(first) +
                           (few_features ? " and whole balls" : "") +
                           " no pose explained the scan");
  *result = std::move(retry);
}

// The drawing's datum frame (datum_alignment.h) in place of the best fit, when comparison points
// name datum targets. A fixed pose is the caller's datum already, and an ambiguous one has no
// single frame to move; either way the targets are still read as comparison points.
void alignToDatumTargets(const Model& model,
                         const Points& points,
                         const PipelineConfig& config,
                         InspectionResult* result) {
  if (!hasDatumTargets(config.comparison_points)) {
    return;
  }
  DatumAlignment& datums = result->datum_alignment;
  if (result->registration != RegistrationStatus::kOk) {
    datums.requested = true;
    datums.T_cad_scan_best_fit = result->T_cad_scan;
    datums.message =
        result->registration == RegistrationStatus::kFixed
            ? "not aligned: the fixed pose is the datum frame"
            : "not aligned: the pose is " + std::string(toString(result->registration));
    if (result->registration == RegistrationStatus::kFixed) {
      result->warnings.push_back(
          "the datum targets do not move a fixed pose (--fixed-pose, "
          "ALIGN_FIXED): they are read as comparison points only");
    }
    return;
  }
  datums = alignToDatums(model.query(),
                         points,
                         result->T_cad_scan,
                         config.comparison_points,
                         config.datum_precedence,
                         model.cellSize(),
                         config.deviation.max_distance_ratio * model.bounds().diagonal());
  if (datums.aligned) {
    result->T_cad_scan = datums.T_cad_scan;
  }
}

// The normals the deviation is measured along: the scan's own (a scanner's, a range image's
// view, a delivered mesh's winding, which the mesh estimator sums over its faces into
// `analysed`), never those a cloud's analysis estimated: a thinned dense cloud shares them
// among the points of a voxel, both sides of a thin wall included. Empty when it has none.
Points ownNormals(const Scan& scan, const ViewHints& hints, const Points& analysed) {
  if (scan.normals.size() == scan.points.size()) {
    return scan.normals;
  }
  if (hints.normals.size() == scan.points.size()) {
    return hints.normals;
  }
  return scan.faces.empty() ? Points() : analysed;
}

// clean → descriptors → registration → deviation, stopping at the first stage that is not ok
// or that the caller cancels.
void runStages(const Model& model,
               const Scan& scan,
               const Alignment& alignment,
               const PipelineConfig& config,
               const ProgressCallback& progress,
               Stopwatch* watch,
               InspectionResult* result) {
  std::size_t cropped = 0;
  const bool crop = !config.input.crop_box.empty();
  const Scan inside =
      crop ? cropToBox(scan, config.input.crop_box, config.input.crop_frame_from_scan, &cropped)
           : Scan();
  CleanScanResult cleaned = cleanWithGridFaces(crop ? inside : scan, model.bounds(), config.input);
  watch->lap("clean");
  result->counts.cropped = cropped;
  // The cropped points were made NaN for the cleaning to drop; they are not the scanner's NaN.
  // (A scan refused before the cleaning counted anything has counted nothing.)
  result->counts.non_finite = cleaned.non_finite >= cropped ? cleaned.non_finite - cropped : 0;
  result->status = cleaned.status;
  if (!result->status.ok() || !watch->proceed("supports", 0.01)) {
    return;
  }
  // The scan's own noise sizes the support's band here, the cloud curvature fit below, and
  // bounds the residual of an acceptable pose later (registerScan).
  const double r_1 = model.descriptors().radii.front();
  result->scan_noise = estimateScanNoise(cleaned.scan.points, 2.0 * r_1);
  const SupportResult supports = findSupports(cleaned.scan.points,
                                              result->scan_noise,
                                              model.bounds().diagonal(),
                                              model.thickness(),
                                              config.support);
  if (supports.removed > 0) {
    cleaned = withoutSupports(cleaned.scan, supports, model.bounds(), config.input);
    result->counts.support_points = supports.removed;
    const std::vector<std::string> found = supports.describe();
    result->warnings.insert(result->warnings.end(), found.begin(), found.end());
    result->status = cleaned.status;
    if (!result->status.ok()) {
      result->status.message = "after removing the support (" + std::to_string(supports.removed) +
                               " points): " + result->status.message;
      return;
    }
    result->scan_noise = estimateScanNoise(cleaned.scan.points, 2.0 * r_1);
  }
  watch->lap("supports");
  result->counts.scan_points = cleaned.scan.points.size();
  result->counts.scan_faces = cleaned.scan.faces.size();
  if (!watch->proceed("descriptors", 0.02)) {
    return;
  }
  // The CAD's radii, so a partial scan gets the same descriptor as the full part.
  // A range image's grid gives the deviation and the defects their connectivity, but its
  // triangles' curvature drowns in noise above the pixel spacing: its descriptors come from
  // the cloud estimator, with normals oriented towards the sensor when the grid says it was
  // seen from the origin (view_hints.h). Delivered meshes keep the mesh estimator.
  const bool range_image = scan.faces.empty() && scan.isOrganized();
  const ViewHints hints =
      range_image && scan.normals.empty() ? rangeImageViewHints(cleaned.scan) : ViewHints();
  const DescriptorResult descriptors =
      computeDescriptors(cleaned.scan.points,
                         range_image ? Triangles() : cleaned.scan.faces,
                         hints.normals.empty() ? cleaned.scan.normals : hints.normals,
                         model.descriptors().radii,
                         config.descriptor,
                         result->scan_noise);
  watch->lap("descriptors");
  result->status = descriptors.status;
  if (!result->status.ok()) {
    return;
  }
  // A scanner's normals, a delivered mesh's winding and a range image's view point out of
  // the material; normals this pipeline estimated otherwise may not.
  const bool oriented = !scan.normals.empty() || !scan.faces.empty() || !hints.normals.empty();
  const Points& points = cleaned.scan.points;
  switch (alignment.mode) {
    case Alignment::Mode::kSearch:
      registerWidening(model, points, descriptors, oriented, config, progress, result);
      break;
    case Alignment::Mode::kRefine:
      registerFrom(model, points, descriptors, oriented, alignment.pose, config, progress, result);
      break;
    case Alignment::Mode::kFixed:
      registerFixed(model, points, descriptors, oriented, alignment.pose, config, progress, result);
      break;
  }
  if (result->registration == RegistrationStatus::kFailed || !watch->proceed("deviation", 0.9)) {
    return;
  }
  watch->start = Clock::now();
  const Points point_normals = oriented ? descriptors.pointNormals(points.size()) : Points();
  // registerFrom() refits its own pose, before it measures the offset from the given one.
  if (alignment.mode == Alignment::Mode::kSearch &&
      result->registration == RegistrationStatus::kOk) {
    fitToAlignedRegions(model, points, point_normals, config, result);
  }
  alignToDatumTargets(model, points, config, result);
  measurePart(model,
              cleaned.scan,
              ownNormals(cleaned.scan, hints, point_normals),
              descriptors,
              config,
              result);
  if (alignment.mode == Alignment::Mode::kFixed) {
    result->pose_uncertainty = PoseUncertainty();  // no fit, so no spread of one
  }
  watch->lap("deviation");
}

}  // namespace

std::string InspectionResult::regionName(int region) const {
  return region >= 0 && static_cast<std::size_t>(region) < regions.size()
             ? regions[static_cast<std::size_t>(region)].name
             : std::string();
}

const char* toString(RegistrationStatus status) {
  switch (status) {
    case RegistrationStatus::kOk:
      return "ok";
    case RegistrationStatus::kAmbiguous:
      return "ambiguous";
    case RegistrationStatus::kFailed:
      return "failed";
    case RegistrationStatus::kFixed:
      return "fixed";
  }
  return "failed";
}

const char* toString(Verdict verdict) {
  switch (verdict) {
    case Verdict::kPass:
      return "PASS";
    case Verdict::kFail:
      return "FAIL";
    case Verdict::kNotEvaluated:
      return "NOT_EVALUATED";
  }
  return "NOT_EVALUATED";
}

std::vector<std::string> validate(const PipelineConfig& config) {
  std::vector<std::string> errors;
  const InputConfig& input = config.input;
  if (input.min_points < 3) {
    errors.push_back("input.min_points must be at least 3");
  }
  if (input.max_points < input.min_points) {
    errors.push_back("input.max_points must be at least input.min_points");
  }
  if (!(input.max_extent_ratio > 1.0)) {
    errors.push_back("input.max_extent_ratio must be > 1");
  }
  if (!(input.min_thickness_ratio >= 0.0 && input.min_thickness_ratio < 1.0)) {
    errors.push_back("input.min_thickness_ratio must be in [0, 1)");
  }
  const std::vector<double>& box = input.crop_box;
  const bool box_ok =
      box.empty() ||
      (box.size() == 6 &&
       std::all_of(box.begin(), box.end(), [](double v) { return std::isfinite(v); }) &&
       box[0] < box[3] && box[1] < box[4] && box[2] < box[5]);
  if (!box_ok) {
    errors.push_back(
        "input.crop_box must be empty or six finite numbers [x_min, y_min, z_min, x_max, y_max, "
        "z_max] with each minimum below its maximum");
  }
  if (!input.crop_frame_from_scan.matrix().allFinite()) {
    errors.push_back("input.crop_frame_from_scan must be a finite transform");
  }
  for (const auto& list : {validate(config.support),
                           validate(config.descriptor),
                           validate(config.features),
                           validate(config.correspondence),
                           validate(config.registration),
                           validate(config.icp)}) {
    errors.insert(errors.end(), list.begin(), list.end());
  }
  for (const auto& list : {validate(config.tolerance),
                           validate(config.deviation),
                           validate(config.defects),
                           validate(config.regions),
                           validate(config.comparison_points),
                           validate(config.datum_precedence, config.comparison_points)}) {
    errors.insert(errors.end(), list.begin(), list.end());
  }
  const VerdictConfig& verdict = config.verdict;
  if (!(verdict.min_in_tolerance_fraction >= 0.0 && verdict.min_in_tolerance_fraction <= 1.0)) {
    errors.push_back("verdict.min_in_tolerance_fraction must be in [0, 1]");
  }
  if (!(verdict.min_coverage >= 0.0 && verdict.min_coverage <= 1.0)) {
    errors.push_back("verdict.min_coverage must be in [0, 1]");
  }
  if (!(verdict.measurement_uncertainty >= 0.0 && std::isfinite(verdict.measurement_uncertainty))) {
    errors.push_back("verdict.measurement_uncertainty must be finite and >= 0 [m]");
  }
  return errors;
}

namespace {

InspectionResult run(const Model& model,
                     const Scan& scan,
                     const Alignment& alignment,
                     const PipelineConfig& config,
                     const ProgressCallback& progress) {
  const auto errors = validate(config);
  if (!errors.empty()) {
    throw std::invalid_argument("invalid pipeline configuration: " + joinMessages(errors));
  }
  const auto start = Clock::now();
  InspectionResult result;
  result.counts.cad_vertices = model.mesh().vertices.size();
  Stopwatch watch{&result, &progress};
  if (descriptorSettingsKey(model.descriptorConfig()) != descriptorSettingsKey(config.descriptor)) {
    // Descriptors computed two ways do not match: every correspondence would be a guess.
    result.status = Status::failure(
        StatusCode::kInvalidInput,
        "the model's descriptors were computed with other descriptor settings than this "
        "inspection's: load the model with the pipeline's descriptor settings");
  } else if (alignment.mode != Alignment::Mode::kSearch &&
             !isRigidTransform(alignment.pose.matrix(), kInitialPoseRigidity)) {
    result.status = Status::failure(
        StatusCode::kInvalidInput,
        std::string(alignment.mode == Alignment::Mode::kFixed ? "the fixed" : "the initial") +
            " pose is not a rigid transform (a finite rotation with orthonormal axes, "
            "determinant +1, and a finite translation)");
  } else if (watch.proceed("clean", 0.0)) {
    runStages(model, scan, alignment, config, progress, &watch, &result);
  }
  judge(config, &result);
  result.timings.push_back({"total", secondsSince(start)});
  return result;
}

}  // namespace

InspectionResult inspect(const Model& model,
                         const Scan& scan,
                         const PipelineConfig& config,
                         const ProgressCallback& progress) {
  return run(model, scan, Alignment(), config, progress);
}

InspectionResult inspectFrom(const Model& model,
                             const Scan& scan,
                             const Eigen::Isometry3d& initial_T_cad_scan,
                             const PipelineConfig& config,
                             const ProgressCallback& progress) {
  return run(model, scan, {Alignment::Mode::kRefine, initial_T_cad_scan}, config, progress);
}

InspectionResult inspectAt(const Model& model,
                           const Scan& scan,
                           const Eigen::Isometry3d& T_cad_scan,
                           const PipelineConfig& config,
                           const ProgressCallback& progress) {
  return run(model, scan, {Alignment::Mode::kFixed, T_cad_scan}, config, progress);
}

}  // namespace freeform_inspection
