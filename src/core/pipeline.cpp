// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "freeform_inspection/geodesic.h"
#include "freeform_inspection/organized_mesh.h"

namespace freeform_inspection {
namespace {

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

struct Stopwatch {
  InspectionResult* result;
  Clock::time_point start = Clock::now();
  void lap(const std::string& stage) {
    result->timings.push_back({stage, secondsSince(start)});
    start = Clock::now();
  }
};

// A refined candidate pose and how much of the scan it explains.
struct RefinedPose {
  Eigen::Isometry3d T_cad_scan;
  double score = 0.0;
};

// A short ICP on the verification cells and the score after it: a coarse fit a few degrees off
// scores low until refined, and a flip that survived verification stays low.
RefinedPose refineQuickly(const Model& model,
                          const Eigen::Isometry3d& pose,
                          const VerificationSet& set,
                          const PipelineConfig& config) {
  const double truncation = config.registration.verification_distance_cells * model.cellSize();
  IcpConfig quick = config.icp;
  quick.max_iterations = std::min(quick.max_iterations, 15);
  const IcpResult icp =
      refinePose(model.query(), set.points, pose, truncation, model.bounds().diagonal(), quick);
  const Eigen::Isometry3d refined =
      icp.status.ok() || icp.status.code == StatusCode::kNotConverged ? icp.T_cad_scan : pose;
  return {refined,
          verificationScore(
              refined, set, model.query(), truncation, config.registration.normal_tolerance_deg)};
}

// refineQuickly() for many starts: one parallel region over the poses (the inner batch queries
// then run single-threaded), results in input order whatever the thread count.
std::vector<RefinedPose> refineAll(const Model& model,
                                   const std::vector<Eigen::Isometry3d>& starts,
                                   const VerificationSet& set,
                                   const PipelineConfig& config) {
  std::vector<RefinedPose> refined(starts.size());
  const auto count = static_cast<long>(starts.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (long i = 0; i < count; ++i) {
    const auto u = static_cast<std::size_t>(i);
    refined[u] = refineQuickly(model, starts[u], set, config);
  }
  return refined;
}

// The best verified hypotheses, refined; then the symmetric twins S·T and S⁻¹·T of the best
// (symmetry.h), so a symmetric part cannot be reported with one of its twins unseen.
std::vector<RefinedPose> refineHypotheses(const Model& model,
                                          const std::vector<PoseHypothesis>& hypotheses,
                                          const VerificationSet& set,
                                          const PipelineConfig& config) {
  const auto count = std::min<std::size_t>(
      hypotheses.size(), static_cast<std::size_t>(config.registration.refined_hypotheses));
  std::vector<Eigen::Isometry3d> starts;
  for (std::size_t h = 0; h < count; ++h) {
    starts.push_back(hypotheses[h].T_cad_scan);
  }
  std::vector<RefinedPose> refined = refineAll(model, starts, set, config);
  const auto by_score = [](const RefinedPose& a, const RefinedPose& b) {
    return a.score > b.score;
  };
  std::stable_sort(refined.begin(), refined.end(), by_score);
  const Eigen::Isometry3d best = refined.front().T_cad_scan;
  std::vector<Eigen::Isometry3d> twins;
  for (const Symmetry& symmetry : model.symmetries()) {
    twins.push_back(symmetry.S * best);
    twins.push_back(symmetry.S.inverse() * best);
  }
  for (const RefinedPose& twin : refineAll(model, twins, set, config)) {
    refined.push_back(twin);
  }
  std::stable_sort(refined.begin(), refined.end(), by_score);
  return refined;
}

std::string formatLength(double metres) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g mm", metres * 1e3);
  return text;
}

// Features → candidates → triplets → verification → ICP. Fills the registration fields of
// `result`; the status says why when no pose could be trusted.
// `oriented`: the scan's normals point out of the material (see VerificationSet).
void registerScan(const Model& model,
                  const Points& scan_points,
                  const DescriptorResult& scan,
                  bool oriented,
                  const PipelineConfig& config,
                  InspectionResult* result) {
  Stopwatch watch{result};
  const DescriptorResult& cad = model.descriptors();
  const double r_max = cad.radii.back();
  const double cell = model.cellSize();
  // A cell whose largest ball is cut by the edge of a partial scan has descriptors the CAD does
  // not share there: it cannot be a feature.
  GeodesicBallGrower grower(scan.graph);
  const auto whole_ball = [&](int cell) {
    double area = 0.0;
    for (const BallMember& member : grower.grow(cell, r_max)) {
      area += scan.graph.area[static_cast<std::size_t>(member.cell)];
    }
    return area >= config.features.min_ball_area * kPi * r_max * r_max;
  };
  const FeatureResult features =
      selectFeatures(scan.graph.centroids, scan.cell_values, r_max, config.features, whole_ball);
  watch.lap("features");
  result->counts.features = features.cells.size();
  if (!features.status.ok()) {
    result->status = features.status;
    return;
  }
  const CorrespondenceResult candidates = findCandidates(scan.cell_values,
                                                         features.cells,
                                                         cad.cell_values,
                                                         cad.graph.centroids,
                                                         cell,
                                                         config.correspondence);
  watch.lap("correspondences");
  result->counts.candidates = candidates.candidates;
  if (!candidates.status.ok()) {
    result->status = candidates.status;
    return;
  }
  const GlobalRegistrationResult global = registerGlobally(
      scan.graph, cad.graph, candidates, model.query(), cell, r_max, config.registration, oriented);
  if (!global.status.ok()) {
    watch.lap("global_registration");
    result->status = global.status;
    return;
  }
  const VerificationSet set =
      makeVerificationSet(scan.graph, config.registration.verification_points, oriented);
  const std::vector<RefinedPose> refined = refineHypotheses(model, global.hypotheses, set, config);
  watch.lap("global_registration");

  const double coarse_truncation = config.registration.verification_distance_cells * cell;
  const double diagonal = model.bounds().diagonal();
  const Eigen::Vector3d reference = set.centroid();
  // Contenders: distinct refined poses close to the best by the coarse score.
  std::vector<RefinedPose> contenders;
  for (const RefinedPose& pose : refined) {
    const bool apart = std::all_of(contenders.begin(), contenders.end(), [&](const RefinedPose& c) {
      return distinctPoses(c.T_cad_scan, pose.T_cad_scan, reference, 10.0, 3.0 * cell);
    });
    if (apart && pose.score >= 0.8 * refined.front().score) {
      contenders.push_back(pose);
    }
  }
  IcpResult icp = refinePose(model.query(),
                             scan_points,
                             contenders.front().T_cad_scan,
                             coarse_truncation,
                             diagonal,
                             config.icp);
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
    icp = refinePose(model.query(),
                     scan_points,
                     contenders[best].T_cad_scan,
                     coarse_truncation,
                     diagonal,
                     config.icp);
    fine_scores[best] = std::max(fine_scores[best], fineScore(icp.T_cad_scan));
  }
  watch.lap("icp");
  if (!icp.status.ok() && icp.status.code != StatusCode::kNotConverged) {
    result->status = icp.status;
    return;
  }
  if (!icp.converged) {
    result->warnings.push_back(icp.status.message);
  }
  result->T_cad_scan = icp.T_cad_scan;
  result->rmse = icp.rmse;
  result->fitness = icp.fitness;
  result->inlier_distance = icp.inlier_distance;
  result->noise_sigma = icp.sigma;
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
  result->counts.correspondences = static_cast<std::size_t>(
      countExplainedFeatures(icp.T_cad_scan,
                             scan.graph,
                             cad.graph,
                             candidates,
                             config.registration.pair_tolerance_cells * cell));

  result->scan_noise = estimateScanNoise(scan_points, 2.0 * cad.radii.front());
  const double noise_floor = std::max(result->scan_noise, 1e-3 * diagonal);
  const bool stretched = icp.sigma > config.registration.max_residual_ratio * noise_floor &&
                         icp.fitness < config.registration.residual_fitness;
  if (result->score < config.registration.min_score ||
      result->fitness < config.registration.min_fitness || stretched) {
    result->status = Status::failure(
        StatusCode::kRegistrationFailed,
        "no pose explains the scan: best pose explains " + std::to_string(result->score) +
            " of it (registration.min_score " + std::to_string(config.registration.min_score) +
            "), ICP fitness " + std::to_string(result->fitness) + " (registration.min_fitness " +
            std::to_string(config.registration.min_fitness) + "), residual " +
            formatLength(icp.sigma) + " for a scan noise of " + formatLength(result->scan_noise) +
            " (registration.max_residual_ratio " +
            std::to_string(config.registration.max_residual_ratio) + ")");
    // No pose to use: the contract's identity, with the rejected fit's numbers kept for the
    // message and diagnostics.
    result->T_cad_scan = Eigen::Isometry3d::Identity();
    result->rmse = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  // Another distinct pose that explains the scan about as well: say so, with all of them.
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    if (c != best && fine_scores[c] >= config.registration.ambiguity_ratio * fine_scores[best] &&
        distinctPoses(result->T_cad_scan, contenders[c].T_cad_scan, reference, 10.0, 3.0 * cell)) {
      result->alternatives.push_back(contenders[c].T_cad_scan);
    }
  }
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

// Deviation, statistics, shape deviation and defect regions of a registered scan.
void measurePart(const Model& model,
                 const Scan& scan,
                 const DescriptorResult& descriptors,
                 const PipelineConfig& config,
                 InspectionResult* result) {
  DeviationMap& map = result->deviation_map;
  map.points.resize(scan.points.size());
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    map.points[i] = result->T_cad_scan * scan.points[i];
  }
  const double diagonal = model.bounds().diagonal();
  SurfaceDistances distances =
      measureDeviation(model, map.points, config.deviation.max_distance_ratio * diagonal);
  map.deviation = std::move(distances.deviation);
  map.shape_deviation =
      shapeDeviation(descriptors, model.descriptors(), result->T_cad_scan, distances.normals);
  result->deviation =
      summarizeDeviation(map.deviation, config.tolerance, config.deviation.histogram_bins);
  summarizeShapeDeviation(map.shape_deviation, &result->deviation);
  result->deviation.coverage = surfaceCoverage(
      model, map.points, config.deviation.coverage_distance_cells * model.cellSize());
  DefectResult defects =
      findDefects(map.points, scan.faces, map.deviation, config.tolerance, config.defects);
  result->defects = std::move(defects.regions);
  map.defect = std::move(defects.point_region);
  result->scan_faces = scan.faces;
  // A band narrower than the residual noise of the fit flags scattered points, not the part.
  const double band = std::min(config.tolerance.upper, -config.tolerance.lower);
  if (std::isfinite(result->noise_sigma) && band < 3.0 * result->noise_sigma) {
    result->warnings.push_back("the tolerance band (" + formatLength(config.tolerance.lower) +
                               " to " + formatLength(config.tolerance.upper) +
                               ") is narrower than 3x the fit's residual noise (sigma " +
                               formatLength(result->noise_sigma) +
                               "): scattered points fall outside it by noise alone");
  }
}

std::string describeDefect(const DefectRegion& defect) {
  char text[160];
  std::snprintf(text,
                sizeof(text),
                "%s of %.3g mm peak over %.3g mm^2 at (%.4g, %.4g, %.4g) m",
                defect.sign < 0 ? "dent (missing material)" : "bump (excess material)",
                defect.peak * 1e3,
                defect.area * 1e6,
                defect.centroid.x(),
                defect.centroid.y(),
                defect.centroid.z());
  return text;
}

// The part's verdict, kept apart from how sure the registration is.
void judge(const PipelineConfig& config, InspectionResult* result) {
  const DeviationStatistics& stats = result->deviation;
  const std::string band = "[" + formatLength(config.tolerance.lower) + ", " +
                           formatLength(config.tolerance.upper) + "]";
  result->verdict = Verdict::kNotEvaluated;
  if (result->registration == RegistrationStatus::kFailed) {
    result->verdict_reason = "not evaluated: " + result->status.message;
    return;
  }
  if (result->registration == RegistrationStatus::kAmbiguous) {
    result->verdict_reason = "not evaluated: the pose is ambiguous (" + result->status.message +
                             "); the deviation shown is for the best pose";
    return;
  }
  if (stats.evaluated == 0) {
    result->verdict_reason = "not evaluated: no scan point lies on the CAD surface";
    return;
  }
  if (stats.coverage < config.verdict.min_coverage) {
    result->verdict_reason = "not evaluated: the scan covers " + std::to_string(stats.coverage) +
                             " of the CAD surface (" + "verdict.min_coverage " +
                             std::to_string(config.verdict.min_coverage) + ")";
    return;
  }
  if (!result->defects.empty()) {
    result->verdict = Verdict::kFail;
    result->verdict_reason = std::to_string(result->defects.size()) +
                             " region(s) outside the tolerance band " + band +
                             "; largest: " + describeDefect(result->defects.front());
    return;
  }
  if (stats.in_tolerance_fraction < config.verdict.min_in_tolerance_fraction) {
    result->verdict = Verdict::kFail;
    result->verdict_reason = "only " + std::to_string(stats.in_tolerance_fraction) +
                             " of the points lie inside the tolerance band " + band +
                             " (verdict.min_in_tolerance_fraction " +
                             std::to_string(config.verdict.min_in_tolerance_fraction) + ")";
    return;
  }
  result->verdict = Verdict::kPass;
  result->verdict_reason = "no region of " + std::to_string(config.defects.min_points) +
                           " or more connected points outside the tolerance band " + band + "; " +
                           std::to_string(stats.in_tolerance_fraction) + " of " +
                           std::to_string(stats.evaluated) + " points inside it, deviation " +
                           formatLength(stats.min) + " to " + formatLength(stats.max);
}

}  // namespace

const char* toString(RegistrationStatus status) {
  switch (status) {
    case RegistrationStatus::kOk:
      return "ok";
    case RegistrationStatus::kAmbiguous:
      return "ambiguous";
    case RegistrationStatus::kFailed:
      return "failed";
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
  for (const auto& list : {validate(config.descriptor),
                           validate(config.features),
                           validate(config.correspondence),
                           validate(config.registration),
                           validate(config.icp)}) {
    errors.insert(errors.end(), list.begin(), list.end());
  }
  for (const auto& list :
       {validate(config.tolerance), validate(config.deviation), validate(config.defects)}) {
    errors.insert(errors.end(), list.begin(), list.end());
  }
  const VerdictConfig& verdict = config.verdict;
  if (!(verdict.min_in_tolerance_fraction >= 0.0 && verdict.min_in_tolerance_fraction <= 1.0)) {
    errors.push_back("verdict.min_in_tolerance_fraction must be in [0, 1]");
  }
  if (!(verdict.min_coverage >= 0.0 && verdict.min_coverage <= 1.0)) {
    errors.push_back("verdict.min_coverage must be in [0, 1]");
  }
  return errors;
}

InspectionResult inspect(const Model& model, const Scan& scan, const PipelineConfig& config) {
  const auto errors = validate(config);
  if (!errors.empty()) {
    throw std::invalid_argument("invalid pipeline configuration: " + joinMessages(errors));
  }
  const auto start = Clock::now();
  InspectionResult result;
  result.counts.cad_vertices = model.mesh().vertices.size();

  const auto clean_start = Clock::now();
  const CleanScanResult cleaned = cleanWithGridFaces(scan, model.bounds(), config.input);
  result.timings.push_back({"clean", secondsSince(clean_start)});
  result.counts.scan_points = cleaned.scan.points.size();
  result.counts.non_finite = cleaned.non_finite;
  result.counts.scan_faces = cleaned.scan.faces.size();
  result.status = cleaned.status;
  if (result.status.ok()) {
    const auto descriptor_start = Clock::now();
    // The CAD's radii, so a partial scan gets the same descriptor as the full part.
    const DescriptorResult descriptors = computeDescriptors(cleaned.scan.points,
                                                            cleaned.scan.faces,
                                                            cleaned.scan.normals,
                                                            model.descriptors().radii,
                                                            config.descriptor);
    result.timings.push_back({"descriptors", secondsSince(descriptor_start)});
    result.status = descriptors.status;
    if (result.status.ok()) {
      // A scanner's normals and a delivered mesh's winding point out of the material; normals
      // this pipeline estimated (clouds without normals, grids triangulated here) may not.
      const bool oriented = !scan.normals.empty() || !scan.faces.empty();
      registerScan(model, cleaned.scan.points, descriptors, oriented, config, &result);
      if (result.registration != RegistrationStatus::kFailed) {
        const auto deviation_start = Clock::now();
        measurePart(model, cleaned.scan, descriptors, config, &result);
        result.timings.push_back({"deviation", secondsSince(deviation_start)});
      }
    }
  }
  judge(config, &result);
  result.timings.push_back({"total", secondsSince(start)});
  return result;
}

}  // namespace freeform_inspection
