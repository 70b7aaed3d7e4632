// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// The whole registration (features → candidates → triplets → verification → ICP) on generated
// scans at random poses (synthetic_scan.h) whose truth is known. Success as issue 4 defines it:
// rotation error < 2°, error of the scan centroid < 1 % of the CAD diagonal L, status "ok".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "test_shapes.h"
#include <gtest/gtest.h>
#include <omp.h>

#include "freeform_inspection/features.h"
#include "freeform_inspection/global_registration.h"
#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/pipeline.h"
#include "freeform_inspection/synthetic_scan.h"
#include "freeform_inspection/virtual_scanner.h"

namespace freeform_inspection {
namespace {

const std::string kBlade = std::string(FREEFORM_DATA_DIR) + "/blade/blade.stl";
const std::string kLink =
    std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/kuka_kr10r900_2_link_4.stl";
const std::string kFlange = std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/abb_irb6640_link_6.stl";
const std::string kSheet = std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/bent_sheet_bracket.stl";
const std::string kChannel = std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/hat_channel.stl";
const std::string kBlock = std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/machined_l_block.stl";
const std::string kBlockAscii =
    std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/machined_l_block_ascii.stl";
const std::string kElbow = std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/elbow_casting.stl";
const std::string kCoarsePump = std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/pump_cover_fn16.stl";
const std::string kFinePump = std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/pump_cover_fn64.stl";
const std::string kForearm = std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/ur10e_forearm.stl";
const std::string kElbowDouble =
    std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/elbow_casting_double.ply";

std::shared_ptr<const Model> load(const std::string& path, double scale) {
  const ModelLoadResult loaded = loadModel(path, scale, "test");
  EXPECT_TRUE(loaded.status.ok()) << loaded.status.message;
  return loaded.model;
}

const Model& blade() {
  static const auto model = load(kBlade, 0.001);
  return *model;
}

const Model& link() {
  static const auto model = load(kLink, 1.0);
  return *model;
}

struct PoseError {
  double rotation_deg = std::numeric_limits<double>::infinity();
  double centroid_ratio = std::numeric_limits<double>::infinity();  // × L
};

PoseError poseError(const InspectionResult& result, const SyntheticScan& truth, double diagonal) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  const std::size_t surface = truth.scan.points.size() - truth.outliers;
  for (std::size_t i = 0; i < surface; ++i) {
    centroid += truth.scan.points[i] / static_cast<double>(surface);
  }
  PoseError error;
  error.rotation_deg =
      Eigen::AngleAxisd(result.T_cad_scan.linear().transpose() * truth.T_cad_scan.linear())
          .angle() *
      180.0 / M_PI;
  error.centroid_ratio =
      (result.T_cad_scan * centroid - truth.T_cad_scan * centroid).norm() / diagonal;
  return error;
}

// RMS distance to the CAD, at `pose`, of the scan's surface points within `within` of it (the
// generator appends its outliers after them): to the nearest face turned the point's way, as
// ICP pairs them (on a wall thinner than the noise the nearest face may be its far side).
double surfaceRms(const Model& model,
                  const SyntheticScan& truth,
                  const Eigen::Isometry3d& pose,
                  double within) {
  const double cos80 = std::cos(80.0 * M_PI / 180.0);
  const Points& normals = truth.scan.normals;
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i + truth.outliers < truth.scan.points.size(); ++i) {
    const Eigen::Vector3d normal =
        i < normals.size() ? Eigen::Vector3d(pose.linear() * normals[i]) : Eigen::Vector3d::Zero();
    const ClosestPoint closest =
        model.query().closestFacing(pose * truth.scan.points[i], normal, cos80, true, within);
    if (closest.found) {
      sum += closest.distance * closest.distance;
      ++count;
    }
  }
  return count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
}

SyntheticScan makeCase(const Model& model, SyntheticScanConfig config) {
  const SyntheticScan scan = makeSyntheticScan(model.query(), config);
  EXPECT_TRUE(scan.status.ok()) << scan.status.message;
  return scan;
}

// Registers one generated case and checks it against the truth; `bare` drops the scan's
// normals, as a cloud of bare points delivers it.
void expectRegistered(const Model& model, const SyntheticScanConfig& config, bool bare = false) {
  SCOPED_TRACE("seed " + std::to_string(config.seed) + ", noise " +
               std::to_string(config.noise_ratio) + " L, " + (config.partial ? "partial" : "full") +
               ", outliers " + std::to_string(config.outlier_fraction) +
               (bare ? ", no normals" : ""));
  SyntheticScan truth = makeCase(model, config);
  if (bare) {
    truth.scan.normals.clear();
  }
  const InspectionResult result = inspect(model, truth.scan, PipelineConfig());
  ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  const PoseError error = poseError(result, truth, model.bounds().diagonal());
  EXPECT_LT(error.rotation_deg, 2.0);
  EXPECT_LT(error.centroid_ratio, 0.01);
  EXPECT_GE(result.counts.features, 3u);
  EXPECT_GE(result.counts.candidates, result.counts.features);
  if (config.noise_ratio > 0.0) {
    // At the noise floor: the scan's surface points (the outliers left out) lie the noise itself
    // from the CAD at the found pose; within 3σ a Gaussian's RMS is 0.986 σ. σ is measured, not
    // assumed.
    const double sigma = config.noise_ratio * model.bounds().diagonal();
    const double surface_rms = surfaceRms(model, truth, result.T_cad_scan, 3.0 * sigma);
    EXPECT_LE(surface_rms, 1.0 * sigma);
    EXPECT_GT(surface_rms, 0.8 * sigma);
    // The reported RMS is over every point within the inlier distance, so the outliers that fell
    // that close to the surface count in it (20 % outliers on the blade: 1.007 σ).
    EXPECT_LE(result.rmse, (config.outlier_fraction > 0.0 ? 1.05 : 1.0) * sigma);
    EXPECT_GT(result.rmse, 0.8 * sigma);
    EXPECT_NEAR(result.noise_sigma, sigma, 0.15 * sigma);
  }
}

SyntheticScanConfig caseConfig(std::uint64_t seed, double noise, bool partial, double outliers) {
  SyntheticScanConfig config;
  config.points = 15000;
  config.seed = seed;
  config.noise_ratio = noise;
  config.partial = partial;
  config.outlier_fraction = outliers;
  return config;
}

// One generated case of 30,000 points registered with the defaults, and its pose errors; what
// came back is printed.
struct Registered {
  InspectionResult result;
  PoseError error;
};

Registered registerCase(const Model& model, std::uint64_t seed, double noise, bool partial) {
  SyntheticScanConfig config = caseConfig(seed, noise, partial, 0.0);
  config.points = 30000;
  const SyntheticScan truth = makeCase(model, config);
  Registered out{inspect(model, truth.scan, PipelineConfig()), PoseError()};
  out.error = poseError(out.result, truth, model.bounds().diagonal());
  std::printf("seed %llu: %s, %.3f deg, %.4f L, %zu alternatives\n",
              static_cast<unsigned long long>(seed),
              toString(out.result.registration),
              out.error.rotation_deg,
              out.error.centroid_ratio,
              out.result.alternatives.size());
  return out;
}

// A pose known roughly (a fixture's nominal pose): inspectFrom() refines it without a search. A
// blade view started 4° and 1 % of L off the truth lands where the search's pose does, with no
// features sought; from 30° off it lands there too, warning how far ICP moved it; a start the
// scan does not touch within ICP's first cut-off (2 L away) fails with a reason, and a start that
// is no rigid transform is the caller's error.
TEST(Registration, InitialPoseIsRefinedWithoutASearch) {
  const Model& model = blade();
  const double diagonal = model.bounds().diagonal();
  for (const bool partial : {false, true}) {
    SCOPED_TRACE(partial ? "partial" : "full");
    const SyntheticScan truth = makeCase(model, caseConfig(3, 0.005, partial, 0.0));
    const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 2.0, -1.0).normalized();
    Eigen::Isometry3d off = Eigen::Isometry3d::Identity();
    off.linear() = Eigen::AngleAxisd(4.0 * M_PI / 180.0, axis).toRotationMatrix();
    off.translation() = 0.01 * diagonal * Eigen::Vector3d(0.0, 0.6, 0.8);
    const InspectionResult from =
        inspectFrom(model, truth.scan, off * truth.T_cad_scan, PipelineConfig());
    ASSERT_EQ(from.registration, RegistrationStatus::kOk) << from.status.message;
    const PoseError error = poseError(from, truth, diagonal);
    std::printf("from 4 deg off: %.3f deg, %.5f L\n", error.rotation_deg, error.centroid_ratio);
    EXPECT_LT(error.rotation_deg, 0.5);
    EXPECT_LT(error.centroid_ratio, 0.002);
    EXPECT_EQ(from.counts.features, 0u);
    EXPECT_TRUE(std::none_of(from.timings.begin(), from.timings.end(), [](const StageTiming& t) {
      return t.stage == "global_registration";
    }));
    EXPECT_GT(from.deviation.evaluated, 0u);
    const auto moved_far = [](const InspectionResult& r) {
      return std::any_of(r.warnings.begin(), r.warnings.end(), [](const std::string& w) {
        return w.find("from the initial pose") != std::string::npos;
      });
    };
    EXPECT_FALSE(moved_far(from)) << "4° is within the separation of distinct poses";
    // How far the part sat from the given pose: the 4° turn (about the CAD's origin, so the
    // scan's centroid moved too), less the pose's own error.
    EXPECT_NEAR(from.offset_from_initial_deg, 4.0, 0.2);
    EXPECT_GT(from.offset_from_initial, 0.005 * diagonal);
    // 30° off: ICP still brings it home on the blade, and says how far it moved it.
    Eigen::Isometry3d far_off = off;
    far_off.linear() = Eigen::AngleAxisd(30.0 * M_PI / 180.0, axis).toRotationMatrix();
    const InspectionResult from_far =
        inspectFrom(model, truth.scan, far_off * truth.T_cad_scan, PipelineConfig());
    ASSERT_EQ(from_far.registration, RegistrationStatus::kOk) << from_far.status.message;
    EXPECT_LT(poseError(from_far, truth, diagonal).rotation_deg, 0.5);
    EXPECT_TRUE(moved_far(from_far));
    // The search's own pose agrees with it.
    const InspectionResult searched = inspect(model, truth.scan, PipelineConfig());
    ASSERT_EQ(searched.registration, RegistrationStatus::kOk) << searched.status.message;
    const double apart =
        Eigen::AngleAxisd(searched.T_cad_scan.linear().transpose() * from.T_cad_scan.linear())
            .angle() *
        180.0 / M_PI;
    EXPECT_LT(apart, 0.3);
  }
  const SyntheticScan truth = makeCase(model, caseConfig(3, 0.005, false, 0.0));
  Eigen::Isometry3d away = truth.T_cad_scan;
  away.translation() += Eigen::Vector3d(2.0 * diagonal, 0.0, 0.0);
  const InspectionResult lost = inspectFrom(model, truth.scan, away, PipelineConfig());
  EXPECT_EQ(lost.registration, RegistrationStatus::kFailed);
  EXPECT_FALSE(lost.status.message.empty());
  EXPECT_EQ(lost.verdict, Verdict::kNotEvaluated);
  Eigen::Isometry3d scaled = truth.T_cad_scan;
  scaled.linear() *= 1.1;
  Eigen::Isometry3d not_finite = truth.T_cad_scan;
  not_finite.translation().x() = std::numeric_limits<double>::quiet_NaN();
  for (const Eigen::Isometry3d& bad : {scaled, not_finite}) {
    const InspectionResult refused = inspectFrom(model, truth.scan, bad, PipelineConfig());
    EXPECT_EQ(refused.status.code, StatusCode::kInvalidInput);
    EXPECT_NE(refused.status.message.find("rigid"), std::string::npos) << refused.status.message;
    EXPECT_EQ(refused.registration, RegistrationStatus::kFailed);
  }
}

// A flange with bolt holes has near-twins: a guess 15° and 2 % of L off (turned about a random
// axis through the view's centre, as registration_eval --guess makes it, seed 2) slid onto a
// turn 17° off the truth that put 0.95 of the view on the CAD, and was reported ok. The pose is
// now probed along its weakest motions, as the search probes its best, and the scan sides with
// the truth.
TEST(Registration, InitialPoseOnANearTwinIsProbedBackToTheTruth) {
  static const auto flange = load(kFlange, 1.0);
  ASSERT_TRUE(flange);
  const double diagonal = flange->bounds().diagonal();
  SyntheticScanConfig config = caseConfig(2, 0.005, false, 0.0);
  config.points = 30000;
  const SyntheticScan truth = makeCase(*flange, config);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& point : truth.scan.points) {
    centroid += point;
  }
  centroid = truth.T_cad_scan * (centroid / static_cast<double>(truth.scan.points.size()));
  std::mt19937_64 rng(config.seed ^ 0x9e3779b97f4a7c15ULL);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Eigen::Vector3d axis = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
  const Eigen::Vector3d direction =
      Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
  Eigen::Isometry3d off = Eigen::Isometry3d::Identity();
  off.linear() = Eigen::AngleAxisd(15.0 * M_PI / 180.0, axis).toRotationMatrix();
  off.translation() = centroid - off.linear() * centroid + 0.02 * diagonal * direction;
  const InspectionResult result =
      inspectFrom(*flange, truth.scan, off * truth.T_cad_scan, PipelineConfig());
  ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  const PoseError error = poseError(result, truth, diagonal);
  std::printf("flange from 15 deg off: %.3f deg, %.5f L, %.3f of the surface on the CAD\n",
              error.rotation_deg,
              error.centroid_ratio,
              result.surface_on_cad);
  EXPECT_LT(error.rotation_deg, 0.5);
  EXPECT_LT(error.centroid_ratio, 0.002);
  EXPECT_GT(result.surface_on_cad, 0.99);
  EXPECT_TRUE(std::any_of(result.warnings.begin(), result.warnings.end(), [](const std::string& w) {
    return w.find("weakest motions") != std::string::npos;
  })) << "the move off the pose ICP reached is reported";
  EXPECT_NEAR(result.offset_from_initial_deg, 15.0, 1.0);
}

// The fixed alignment (inspectAt): the deviation at the given pose as it is. At the truth the
// deviation is the noise; 2 % of L off, it is the offset as well, which inspectFrom() from the
// same pose would have fitted away, and the offset says so.
TEST(Registration, FixedPoseIsInspectedWhereItIsGiven) {
  const Model& model = blade();
  const double diagonal = model.bounds().diagonal();
  const double sigma = 0.002 * diagonal;
  const SyntheticScan truth = makeCase(model, caseConfig(3, 0.002, true, 0.0));
  const InspectionResult at_truth =
      inspectAt(model, truth.scan, truth.T_cad_scan, PipelineConfig());
  ASSERT_EQ(at_truth.registration, RegistrationStatus::kFixed) << at_truth.status.message;
  EXPECT_TRUE(at_truth.status.ok());
  EXPECT_TRUE(at_truth.T_cad_scan.isApprox(truth.T_cad_scan, 1e-15));
  EXPECT_GT(at_truth.deviation.rms, 0.8 * sigma);
  EXPECT_LT(at_truth.deviation.rms, 1.1 * sigma);
  EXPECT_LT(at_truth.offset_from_initial_deg, 0.3);
  EXPECT_LT(at_truth.offset_from_initial, 0.002 * diagonal);
  EXPECT_FALSE(at_truth.pose_uncertainty.known);
  EXPECT_EQ(at_truth.counts.features, 0u);
  EXPECT_NE(at_truth.verdict, Verdict::kNotEvaluated) << at_truth.verdict_reason;
  Eigen::Isometry3d off_seat = Eigen::Isometry3d::Identity();
  off_seat.translation() = 0.02 * diagonal * Eigen::Vector3d(0.0, 0.6, 0.8);
  const Eigen::Isometry3d given = off_seat * truth.T_cad_scan;
  const InspectionResult fixed = inspectAt(model, truth.scan, given, PipelineConfig());
  ASSERT_EQ(fixed.registration, RegistrationStatus::kFixed) << fixed.status.message;
  EXPECT_TRUE(fixed.T_cad_scan.isApprox(given, 1e-15));
  EXPECT_GT(fixed.deviation.rms, 3.0 * sigma) << "the offset shows as deviation";
  EXPECT_NEAR(fixed.offset_from_initial, 0.02 * diagonal, 0.002 * diagonal);
  const InspectionResult refined = inspectFrom(model, truth.scan, given, PipelineConfig());
  ASSERT_EQ(refined.registration, RegistrationStatus::kOk) << refined.status.message;
  EXPECT_LT(refined.deviation.rms, 1.1 * sigma) << "refined, the offset is fitted away";
  EXPECT_NEAR(refined.offset_from_initial, fixed.offset_from_initial, 1e-9);
  Eigen::Isometry3d sheared = truth.T_cad_scan;
  sheared.linear()(0, 1) += 0.01;
  const InspectionResult refused = inspectAt(model, truth.scan, sheared, PipelineConfig());
  EXPECT_EQ(refused.status.code, StatusCode::kInvalidInput);
  EXPECT_NE(refused.status.message.find("fixed pose"), std::string::npos) << refused.status.message;
  EXPECT_EQ(refused.verdict, Verdict::kNotEvaluated);
}

// Clutter beside the part that is no plane (a clamp: a block of points), twice the part's points:
// no pose explains the scan; input.crop_box, set around where the part lies in the scan's frame
// (as a fixed scanner's integrator sets it once), takes it away and the part registers.
TEST(Registration, CropBoxTakesAwayClutterBesideThePart) {
  const SyntheticScanConfig config = caseConfig(4, 0.005, false, 0.0);
  SyntheticScan truth = makeCase(blade(), config);
  const BoundingBox part = computeBoundingBox(truth.scan.points);
  const std::size_t part_points = truth.scan.points.size();
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d clamp_min = part.max + 0.05 * part.extent();
  for (std::size_t i = 0; i < 2 * part_points; ++i) {
    truth.scan.points.push_back(
        clamp_min +
        0.5 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).cwiseProduct(part.extent()));
    truth.scan.normals.push_back(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized());
  }
  truth.outliers = 2 * part_points;  // the clutter, last: not in the centroid of the pose error
  const InspectionResult cluttered = inspect(blade(), truth.scan, PipelineConfig());
  EXPECT_NE(cluttered.registration, RegistrationStatus::kOk) << cluttered.status.message;
  PipelineConfig cropped_config;
  const Eigen::Vector3d margin = 0.02 * part.extent();
  cropped_config.input.crop_box = {part.min.x() - margin.x(),
                                   part.min.y() - margin.y(),
                                   part.min.z() - margin.z(),
                                   part.max.x() + margin.x(),
                                   part.max.y() + margin.y(),
                                   part.max.z() + margin.z()};
  const InspectionResult result = inspect(blade(), truth.scan, cropped_config);
  EXPECT_EQ(result.counts.cropped, 2 * part_points);
  EXPECT_EQ(result.counts.scan_points, part_points);
  EXPECT_EQ(result.counts.non_finite, 0u);
  ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  const PoseError error = poseError(result, truth, blade().bounds().diagonal());
  EXPECT_LT(error.rotation_deg, 2.0);
  EXPECT_LT(error.centroid_ratio, 0.01);
}

TEST(Registration, BladeFullViewsAtHalfAPercentNoise) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    expectRegistered(blade(), caseConfig(seed, 0.005, false, 0.0));
  }
}

TEST(Registration, BladePartialViewsAtHalfAPercentNoise) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    expectRegistered(blade(), caseConfig(seed, 0.005, true, 0.0));
  }
}

TEST(Registration, BladePartialViewsWithoutNormals) {
  // A single view of bare points: nothing seen from outside tells its normals' sign, and the
  // centroid vote turns a view of the concave pressure side inside out (every V_k reads
  // 1 − V_k). The scan is then matched both ways (docs/registration.md).
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    expectRegistered(blade(), caseConfig(seed, 0.005, true, 0.0), true);
  }
}

TEST(Registration, BladeWithTwentyPercentOutliers) {
  expectRegistered(blade(), caseConfig(4, 0.005, false, 0.2));
}

TEST(Registration, SparseScansOfThreeThousandPoints) {
  // Spacing ≈ r_1: the surface edges stretch to 3 spacings so the scan stays one surface (at r_1
  // alone it fell apart and no rare feature was found, 0/16 in docs/benchmarks.md).
  for (std::uint64_t seed = 13; seed <= 14; ++seed) {
    SyntheticScanConfig config = caseConfig(seed, 0.005, false, 0.0);
    config.points = 3000;
    expectRegistered(blade(), config);
  }
}

TEST(Registration, CastLinkFullAndPartialViews) {
  expectRegistered(link(), caseConfig(5, 0.005, false, 0.0));
  expectRegistered(link(), caseConfig(6, 0.005, true, 0.0));
}

// Noise of 2 % of L (the paper's ±2 %; σ = 3.2 mm on the blade, thicker than most of it): the
// curvature fit grows with the measured noise and ICP runs on the neighbourhood planes
// (descriptors.md, registration.md). Before, no scan at 2 % registered. The fit's numbers are
// the measured points': the 3σ trimming drops more than a Gaussian's tails here (noise pushes
// points towards other faces), so the RMS reads 0.7-0.9 σ.
TEST(Registration, TwoPercentNoiseFullViews) {
  const std::vector<std::pair<const Model*, std::uint64_t>> cases = {
      {&blade(), 21}, {&blade(), 22}, {&link(), 23}};
  for (const auto& [model, seed] : cases) {
    const SyntheticScanConfig config = caseConfig(seed, 0.02, false, 0.0);
    SCOPED_TRACE("seed " + std::to_string(seed));
    const SyntheticScan truth = makeCase(*model, config);
    const InspectionResult result = inspect(*model, truth.scan, PipelineConfig());
    ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
    const double diagonal = model->bounds().diagonal();
    const double sigma = config.noise_ratio * diagonal;
    const PoseError error = poseError(result, truth, diagonal);
    std::printf("seed %llu: %.3f deg, %.4f L, RMS %.3f σ, robust σ %.3f σ, scan noise %.3f σ\n",
                static_cast<unsigned long long>(seed),
                error.rotation_deg,
                error.centroid_ratio,
                result.rmse / sigma,
                result.noise_sigma / sigma,
                result.scan_noise / sigma);
    EXPECT_LT(error.rotation_deg, 2.0);
    EXPECT_LT(error.centroid_ratio, 0.01);
    EXPECT_LE(result.rmse, 1.0 * sigma);
    EXPECT_GT(result.rmse, 0.6 * sigma);
    EXPECT_NEAR(result.scan_noise, sigma, 0.3 * sigma);
  }
}

// A stamped bracket (test/data/make_parts.py: a 2 mm sheet bent by 90°, legs of 100 and 70 mm,
// a bead on the long leg) seen from one side, 30,000 points. Before the retries and the facing
// pairs (registration.md, "Slid, swapped and thin"), a view at 0.1 % noise (seed 2) came back
// slid 2 mm along the sheet's width, and views at 1 % (σ = 1.8 mm, about the sheet's thickness)
// were pulled into the sheet by 1 % of L or had their legs swapped: of these eight, two were
// wrong poses reported ok (0.1 % seed 2, 1 % seed 3), two failed and one was ambiguous.
// At 1 % the poses are not at the noise floor (0.04-0.52° and 0.66-0.81 % of L off; the
// surface points' RMS reads 0.99-1.0 σ), so only the pose is asserted here.
TEST(Registration, BentSheetPartialViews) {
  static const auto sheet = load(kSheet, 1.0);
  const double diagonal = sheet->bounds().diagonal();
  for (const double noise : {0.001, 0.01}) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      SyntheticScanConfig config = caseConfig(seed, noise, true, 0.0);
      config.points = 30000;
      SCOPED_TRACE("seed " + std::to_string(seed) + ", noise " + std::to_string(noise));
      const SyntheticScan truth = makeCase(*sheet, config);
      const InspectionResult result = inspect(*sheet, truth.scan, PipelineConfig());
      ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
      const PoseError error = poseError(result, truth, diagonal);
      const double sigma = noise * diagonal;
      std::printf("noise %.3f seed %llu: %.3f deg, %.4f L, surface RMS %.3f σ\n",
                  noise,
                  static_cast<unsigned long long>(seed),
                  error.rotation_deg,
                  error.centroid_ratio,
                  surfaceRms(*sheet, truth, result.T_cad_scan, 3.0 * sigma) / sigma);
      EXPECT_LT(error.rotation_deg, 2.0);
      EXPECT_LT(error.centroid_ratio, 0.01);
    }
  }
}

// Views of sheet parts whose confusion is a half turn about an axis off the centroid
// (registration.md, "Turns placed by the features"): the hat channel (test/data/make_parts.py)
// turned about its cross axis or its vertical axis, the flanges swapped, and the bracket turned
// about its bend's bisector, legs swapped. Each of these was a wrong pose reported ok, explaining
// 87-94 % of the view's surface: the turns about the centroid of the spread's axes missed the
// axes by 18° (the unequal flanges tilt them) or landed 8-60 mm off.
TEST(Registration, SheetMetalViewsTurnedAboutAnAxisOffTheirCentroid) {
  static const auto channel = load(kChannel, 1.0);
  static const auto bracket = load(kSheet, 1.0);
  struct View {
    const char* part;
    const Model* model;
    double noise;
    std::uint64_t seed;
  };
  for (const View& view : {View{"hat channel", channel.get(), 0.001, 1},
                           View{"hat channel", channel.get(), 0.001, 3},
                           View{"bracket", bracket.get(), 0.005, 3}}) {
    SyntheticScanConfig config = caseConfig(view.seed, view.noise, true, 0.0);
    config.points = 30000;
    SCOPED_TRACE(std::string(view.part) + " seed " + std::to_string(view.seed));
    const SyntheticScan truth = makeCase(*view.model, config);
    const InspectionResult result = inspect(*view.model, truth.scan, PipelineConfig());
    ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
    const PoseError error = poseError(result, truth, view.model->bounds().diagonal());
    std::printf("%s seed %llu: %.3f deg, %.4f L, surface on CAD %.3f\n",
                view.part,
                static_cast<unsigned long long>(view.seed),
                error.rotation_deg,
                error.centroid_ratio,
                result.surface_on_cad);
    EXPECT_LT(error.rotation_deg, 2.0);
    EXPECT_LT(error.centroid_ratio, 0.01);
    EXPECT_GT(result.surface_on_cad, 0.99);
  }
}

// The bracket turned about its bend's bisector, legs swapped, where the turned pose explains 98 %
// of the view (registration.md, "Half turns about the walls up to 99 %"): above the 95 % that
// starts every turn, both views were wrong poses reported ok. The 15,000-point view is right
// now; the 30,000-point one is ambiguous, the truth (quickly refined) among its alternatives.
TEST(Registration, BentSheetWithItsLegsSwappedIsNeverAConfidentWrongPose) {
  static const auto bracket = load(kSheet, 1.0);
  const double diagonal = bracket->bounds().diagonal();
  struct View {
    std::size_t points;
    double noise;
    bool ok;  // false: ambiguous, with the truth among the alternatives
  };
  for (const View& view : {View{15000, 0.005, true}, View{30000, 0.01, false}}) {
    SyntheticScanConfig config = caseConfig(11, view.noise, true, 0.0);
    config.points = view.points;
    SCOPED_TRACE(std::to_string(view.points) + " points, noise " + std::to_string(view.noise));
    const SyntheticScan truth = makeCase(*bracket, config);
    const InspectionResult result = inspect(*bracket, truth.scan, PipelineConfig());
    const PoseError error = poseError(result, truth, diagonal);
    std::printf("%zu points: %s, %.3f deg, %.4f L, surface on CAD %.3f\n",
                view.points,
                toString(result.registration),
                error.rotation_deg,
                error.centroid_ratio,
                result.surface_on_cad);
    if (view.ok) {
      ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
      EXPECT_LT(error.rotation_deg, 2.0);
      EXPECT_LT(error.centroid_ratio, 0.01);
      continue;
    }
    ASSERT_EQ(result.registration, RegistrationStatus::kAmbiguous) << result.status.message;
    const bool truth_offered = std::any_of(
        result.alternatives.begin(), result.alternatives.end(), [&](const Eigen::Isometry3d& a) {
          InspectionResult alternative;
          alternative.T_cad_scan = a;
          const PoseError offered = poseError(alternative, truth, diagonal);
          std::printf(
              "  alternative: %.3f deg, %.4f L\n", offered.rotation_deg, offered.centroid_ratio);
          // Quickly refined on the verification cells only: 0.12°, 1.5 % of L along the sheet.
          return offered.rotation_deg < 2.0 && offered.centroid_ratio < 0.02;
        });
    EXPECT_TRUE(truth_offered);
  }
}

// Views whose truth is a twin of a turned pose, where the self-match the twin comes from had
// stopped sliding along the part (symmetry.cpp, slidToBest): the hat channel's half turn was
// 40 mm off its best place, so the twin of the turned pose missed the truth and the turned pose
// was reported ok (1 % seed 2, 179.96° off, surface on CAD 0.98); the bracket's 15k-point view
// at 1 % seed 3 likewise (0.95). Now the channel's view is right; the bracket's is ambiguous
// (a poor view: none of the poses it offers is the truth), never a turned pose reported ok.
// A machined L-block seen from one side, at 0.5 and 1 % noise: its legs swapped (a half turn
// about the bisector of its walls, 22 % of L away) the view lay on the CAD but for 13-17 % of
// it and was reported ok. The half turn is among the wall frame's turns (symmetry.cpp,
// wallAxes: the normals' scatter lay 16° off both walls), and the surface votes place it where
// no feature's candidates did (turn_votes_internal.h, surfaceVotedTurnStarts).
TEST(Registration, MachinedBlockViewsWithTheirLegsSwappedAreTurnedBack) {
  static const auto block = load(kBlock, 1.0);
  for (const double noise : {0.005, 0.01}) {
    SyntheticScanConfig config = caseConfig(3, noise, true, 0.0);
    config.points = 30000;
    SCOPED_TRACE("noise " + std::to_string(noise));
    const SyntheticScan truth = makeCase(*block, config);
    const InspectionResult result = inspect(*block, truth.scan, PipelineConfig());
    const PoseError error = poseError(result, truth, block->bounds().diagonal());
    std::printf("noise %.3f: %s, %.3f deg, %.4f L, surface on CAD %.3f\n",
                noise,
                toString(result.registration),
                error.rotation_deg,
                error.centroid_ratio,
                result.surface_on_cad);
    ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
    EXPECT_LT(error.rotation_deg, 2.0);
    EXPECT_LT(error.centroid_ratio, 0.01);
    EXPECT_GT(result.surface_on_cad, 0.99);
  }
}

// The L-block seen from one side at 2 % noise (σ = 2.1 mm, 30,000 points, seed 3). ICP runs on
// the points moved onto their neighbourhood quadrics; while those quadrics took in neighbours
// across the block's edges and bores (turned up to 120° from the point's normal), they bent
// the faces there, and ICP, started even at the truth, slid the view 2.5 % of L along the
// block: reported ok, surface on CAD 0.998. The quadrics now leave out neighbours turned by
// more than 45° (curvature_cloud.cpp, kQuadricSide), and the view registers where it is.
TEST(Registration, MachinedBlockViewAtTwoPercentIsNotSlidAlongTheBlock) {
  static const auto block = load(kBlock, 1.0);
  SyntheticScanConfig config = caseConfig(3, 0.02, true, 0.0);
  config.points = 30000;
  expectRegistered(*block, config);
}

// The L-block's OpenSCAD export as the benchmark reads it (ASCII STL) seen nearly edge-on by the
// camera (`registration_eval --camera --edge-on 10 --noise 0.001`, seed 5: this pose). The first
// pose put 0.29 of the view's surface on the CAD; the retries found a pose with the block's legs
// swapped, a quarter turn about its length, that puts 0.81 there and passed every check: `ok`
// 90° off, where the truth puts 0.998 there. The turns that reach the truth are that pose's, not
// the first's: a second round of retries from the pose the first round chose finds it (with one
// round, kRetryRounds = 1, it was `ok` 90° off: checked by building so).
TEST(Registration, RetriesGoOnFromThePoseTheyFound) {
  static const auto block = load(kBlockAscii, 1.0);
  VirtualScannerConfig camera;
  camera.random_pose = false;
  camera.seed = 5;
  camera.noise_ratio = 0.001;
  camera.T_sensor_cad.matrix().topRows<3>() << -0.15366833875938213, 0.13219966419365234,
      0.97923913854074351, -0.012519376498442205, 0.98809520140930718, 0.013194412956845383,
      0.15327680978747252, -0.040780654046780579, 0.0073426572051660914, 0.99113528655467098,
      -0.13265341733765335, 0.13168020902837294;
  const VirtualScan view = makeVirtualScan(block->query(), camera);
  ASSERT_TRUE(view.status.ok()) << view.status.message;
  EXPECT_EQ(view.counts.valid, 37667u);
  const InspectionResult result = inspect(*block, view.scan, PipelineConfig());
  ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  SyntheticScan truth;  // the measured points and the view's truth, for poseError()
  truth.T_cad_scan = view.T_cad_scan;
  for (const Eigen::Vector3d& p : view.scan.points) {
    if (p.allFinite()) {
      truth.scan.points.push_back(p);
    }
  }
  const PoseError error = poseError(result, truth, block->bounds().diagonal());
  EXPECT_LT(error.rotation_deg, 0.5);
  EXPECT_LT(error.centroid_ratio, 0.002);
  EXPECT_GT(result.surface_on_cad, 0.99);
}

// Partial views of a cast pipe elbow at 2 % noise: one (seed 2) lay 40° along the bend, where
// the view explains 99 % of itself and the truth 99.5 %, and ICP from every probe within four
// cells stayed there. The probes far along the weakest motion (pipeline.cpp, kFarProbeReaches)
// reach the truth, which the scan does not clearly prefer: the view is ambiguous, not a
// confident wrong pose. The other two views stay right.
TEST(Registration, AViewOfABendIsNeverAConfidentPoseTurnedAlongIt) {
  static const auto elbow = load(kElbow, 1.0);
  int right = 0;
  for (const std::uint64_t seed : {1, 2, 3}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto [result, error] = registerCase(*elbow, seed, 0.02, true);
    const bool is_right = error.rotation_deg < 2.0 && error.centroid_ratio < 0.01;
    EXPECT_NE(result.registration, RegistrationStatus::kFailed) << result.status.message;
    if (result.registration == RegistrationStatus::kOk) {
      EXPECT_TRUE(is_right) << "a wrong pose reported ok";
      right += is_right ? 1 : 0;
    }
  }
  EXPECT_GE(right, 2);
}

// Another export of the same elbow (OpenSCAD's ASCII coordinates kept as double): its partial
// view at 0.5 % noise (seed 2) was reported ok 38° along the bend, explaining 96 % of itself.
// The probes 0.2-0.3 L along the weakest motion land 10-15° from the truth, where ICP on the
// verification cells with the score's 2.5-cell cut-off kept too few pairs and stopped 40° off;
// with 4 cells (kFarProbeCutoffScale) it reaches the truth, which the scan clearly prefers.
TEST(Registration, FarProbesAlongABendPairFarEnoughToReachTheTruth) {
  static const auto elbow = load(kElbowDouble, 1.0);
  const double diagonal = elbow->bounds().diagonal();
  SyntheticScanConfig config = caseConfig(2, 0.005, true, 0.0);
  config.points = 30000;
  const SyntheticScan truth = makeCase(*elbow, config);
  const InspectionResult result = inspect(*elbow, truth.scan, PipelineConfig());
  const PoseError error = poseError(result, truth, diagonal);
  std::printf("%s, %.3f deg, %.4f L\n",
              toString(result.registration),
              error.rotation_deg,
              error.centroid_ratio);
  ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  EXPECT_LT(error.rotation_deg, 0.5);
  EXPECT_LT(error.centroid_ratio, 0.002);
}

TEST(Registration, SheetMetalTwinsOfASlidSelfMatchLeaveNoTurnedPoseOk) {
  static const auto channel = load(kChannel, 1.0);
  static const auto bracket = load(kSheet, 1.0);
  struct View {
    const char* part;
    const Model* model;
    std::uint64_t seed;
    std::size_t points;
    bool may_be_ambiguous;
  };
  for (const View& view : {View{"hat channel", channel.get(), 2, 30000, false},
                           View{"bracket", bracket.get(), 3, 15000, true}}) {
    SyntheticScanConfig config = caseConfig(view.seed, 0.01, true, 0.0);
    config.points = view.points;
    SCOPED_TRACE(view.part);
    const SyntheticScan truth = makeCase(*view.model, config);
    const InspectionResult result = inspect(*view.model, truth.scan, PipelineConfig());
    const PoseError error = poseError(result, truth, view.model->bounds().diagonal());
    std::printf("%s: %s, %.3f deg, %.4f L, surface on CAD %.3f\n",
                view.part,
                result.registration == RegistrationStatus::kOk ? "ok" : "not ok",
                error.rotation_deg,
                error.centroid_ratio,
                result.surface_on_cad);
    if (view.may_be_ambiguous && result.registration == RegistrationStatus::kAmbiguous) {
      EXPECT_FALSE(result.alternatives.empty());  // not a confident answer, right or wrong
      continue;
    }
    ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
    EXPECT_LT(error.rotation_deg, 2.0);
    EXPECT_LT(error.centroid_ratio, 0.01);
  }
}

// 100k points at 1-2 % noise: the curvature fit needs a share of them to reach 3 σ (descriptor.h,
// noise_fit_budget). With every point analysed the fit stopped short of the noise and both
// cases failed (1 % seed 1, 2 % seed 2: `failed`, 2.0 s and 5.0 s of descriptors).
TEST(Registration, DenseNoisyScansRegister) {
  for (const auto& [noise, seed] : {std::pair<double, std::uint64_t>{0.01, 1}, {0.02, 2}}) {
    SyntheticScanConfig config = caseConfig(seed, noise, false, 0.0);
    config.points = 100000;
    SCOPED_TRACE("seed " + std::to_string(seed) + ", noise " + std::to_string(noise));
    const SyntheticScan truth = makeCase(blade(), config);
    const InspectionResult result = inspect(blade(), truth.scan, PipelineConfig());
    ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
    const double diagonal = blade().bounds().diagonal();
    const double sigma = noise * diagonal;
    const PoseError error = poseError(result, truth, diagonal);
    std::printf("100k points, %.0f %% noise: %.3f deg, %.4f L, RMS %.3f σ\n",
                100.0 * noise,
                error.rotation_deg,
                error.centroid_ratio,
                result.rmse / sigma);
    EXPECT_LT(error.rotation_deg, 2.0);
    EXPECT_LT(error.centroid_ratio, 0.01);
    EXPECT_LE(result.rmse, 1.0 * sigma);
  }
}

TEST(Registration, NoiseFreePartialScanIsExact) {
  const SyntheticScan truth = makeCase(blade(), caseConfig(7, 0.0, true, 0.0));
  const InspectionResult result = inspect(blade(), truth.scan, PipelineConfig());
  ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  const PoseError error = poseError(result, truth, blade().bounds().diagonal());
  EXPECT_LT(error.rotation_deg, 1e-3);
  EXPECT_LT(error.centroid_ratio, 1e-5);
  EXPECT_GT(result.fitness, 0.99);
}

TEST(Registration, SameInputSamePoseWhateverTheThreadCount) {
  const SyntheticScan truth = makeCase(blade(), caseConfig(8, 0.005, true, 0.0));
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const InspectionResult one = inspect(blade(), truth.scan, PipelineConfig());
  omp_set_num_threads(2);
  const InspectionResult two = inspect(blade(), truth.scan, PipelineConfig());
  omp_set_num_threads(threads);
  ASSERT_EQ(one.registration, RegistrationStatus::kOk) << one.status.message;
  EXPECT_EQ(one.T_cad_scan.matrix(), two.T_cad_scan.matrix());
  EXPECT_EQ(one.counts.features, two.counts.features);
  EXPECT_EQ(one.counts.candidates, two.counts.candidates);
}

TEST(Registration, ReportsCountsAndEveryStageTiming) {
  const SyntheticScan truth = makeCase(blade(), caseConfig(9, 0.005, false, 0.0));
  const InspectionResult result = inspect(blade(), truth.scan, PipelineConfig());
  std::vector<std::string> stages;
  for (const auto& timing : result.timings) {
    stages.push_back(timing.stage);
    EXPECT_GE(timing.seconds, 0.0);
  }
  const std::vector<std::string> expected = {"clean",
                                             "supports",
                                             "descriptors",
                                             "features",
                                             "correspondences",
                                             "global_registration",
                                             "icp",
                                             "verification",
                                             "deviation",
                                             "total"};
  EXPECT_EQ(stages, expected);
  EXPECT_LE(result.counts.correspondences, result.counts.features);
  EXPECT_GE(result.counts.correspondences, 1u);
  EXPECT_NE(result.status.message.find("registered"), std::string::npos);
}

TEST(Registration, WiderCandidateSearchRegistersWhatTheFirstMissed) {
  // One candidate per feature (the best descriptor match) leaves no consistent true triplet on a
  // noisy scan; the second search with 32 per feature, run only because the first found no pose,
  // must register it, report why, and count each stage's time once. Seed 2: seeds 2-8 all
  // fail with one candidate (seed 1 no longer does since a noisy cloud's cells are binned from
  // its planes).
  const SyntheticScan truth = makeCase(blade(), caseConfig(2, 0.005, false, 0.0));
  PipelineConfig narrow;
  narrow.correspondence.min_candidates = 1;
  narrow.correspondence.max_candidates = 1;
  narrow.correspondence.retry_candidates = 0;  // off
  const InspectionResult first = inspect(blade(), truth.scan, narrow);
  ASSERT_EQ(first.registration, RegistrationStatus::kFailed);
  EXPECT_EQ(first.status.code, StatusCode::kRegistrationFailed) << first.status.message;

  PipelineConfig widening = narrow;
  widening.correspondence.retry_candidates = 32;
  const InspectionResult result = inspect(blade(), truth.scan, widening);
  ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  const PoseError error = poseError(result, truth, blade().bounds().diagonal());
  EXPECT_LT(error.rotation_deg, 2.0);
  EXPECT_LT(error.centroid_ratio, 0.01);
  EXPECT_GT(result.counts.candidates, first.counts.candidates);
  EXPECT_TRUE(std::any_of(result.warnings.begin(), result.warnings.end(), [](const auto& w) {
    return w.find("correspondence.retry_candidates") != std::string::npos;
  }));
  std::vector<std::string> stages;
  for (const auto& timing : result.timings) {
    EXPECT_EQ(std::count(stages.begin(), stages.end(), timing.stage), 0) << timing.stage;
    stages.push_back(timing.stage);
  }
  EXPECT_EQ(stages.back(), "total");
}

// The scan without the bands across the CAD's x axis where (x / r_max) mod (keep + gap) ≥ keep:
// a view with stripes of missing data (a shiny part, a scanner that drops fringes), whose
// geodesic balls of radius r_max the gaps cut.
SyntheticScan withBandsMissing(const SyntheticScan& scan, double r_max, double keep, double gap) {
  SyntheticScan banded = scan;
  banded.scan.points.clear();
  banded.scan.normals.clear();
  for (std::size_t i = 0; i < scan.scan.points.size(); ++i) {
    const double x = (scan.T_cad_scan * scan.scan.points[i]).x() / r_max;
    if (x - (keep + gap) * std::floor(x / (keep + gap)) < keep) {
      banded.scan.points.push_back(scan.scan.points[i]);
      banded.scan.normals.push_back(scan.scan.normals[i]);
    }
  }
  return banded;
}

TEST(Registration, SecondSearchTakesFeaturesWhoseBallTheViewCuts) {
  // 30k-point views at 0.1 % noise with bands missing: full views with bands 0.4 r_max wide kept
  // and lost, partial ones 0.5 and 0.5. No r_max ball is whole, so the first search finds too
  // few features for a congruent triplet (full views) or fewer than three (the partial one).
  // The second search accepts balls cut down to half the usual share and must register them.
  // These are the three of seeds 1-8 of each kind that failed before it did (with more
  // candidates for the same features alone, kRetryBallShare = 1: checked by building so); the
  // other thirteen registered either way.
  const double r_max = blade().descriptors().radii.back();
  PipelineConfig once;
  once.correspondence.retry_candidates = 0;  // no second search
  const struct {
    std::uint64_t seed;
    bool partial;
    double band;  // × r_max, kept and lost alike
  } views[] = {{1, false, 0.4}, {2, false, 0.4}, {2, true, 0.5}};
  for (const auto& view : views) {
    SCOPED_TRACE(std::string(view.partial ? "partial" : "full") + " view, seed " +
                 std::to_string(view.seed));
    SyntheticScanConfig config = caseConfig(view.seed, 0.001, view.partial, 0.0);
    config.points = 30000;
    const SyntheticScan truth =
        withBandsMissing(makeCase(blade(), config), r_max, view.band, view.band);
    const InspectionResult first = inspect(blade(), truth.scan, once);
    ASSERT_EQ(first.registration, RegistrationStatus::kFailed);
    EXPECT_EQ(first.status.code, StatusCode::kRegistrationFailed) << first.status.message;

    const InspectionResult result = inspect(blade(), truth.scan, PipelineConfig());
    ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
    const PoseError error = poseError(result, truth, blade().bounds().diagonal());
    EXPECT_LT(error.rotation_deg, 0.5);
    EXPECT_LT(error.centroid_ratio, 0.002);
    EXPECT_GT(result.counts.features, first.counts.features);
    EXPECT_TRUE(std::any_of(result.warnings.begin(), result.warnings.end(), [](const auto& w) {
      return w.find("features whose ball the view cuts") != std::string::npos;
    }));
  }
}

TEST(Registration, CancelDuringTheWiderSearchIsReportedAsCancelled) {
  const SyntheticScan truth = makeCase(blade(), caseConfig(2, 0.005, false, 0.0));
  PipelineConfig widening;
  widening.correspondence.min_candidates = 1;
  widening.correspondence.max_candidates = 1;
  widening.correspondence.retry_candidates = 32;
  int searches = 0;
  const ProgressCallback stop_second = [&](const std::string& stage, double) {
    searches += stage == "features" ? 1 : 0;
    return searches < 2;
  };
  const InspectionResult result = inspect(blade(), truth.scan, widening, stop_second);
  EXPECT_EQ(searches, 2);
  EXPECT_EQ(result.registration, RegistrationStatus::kFailed);
  EXPECT_EQ(result.status.code, StatusCode::kCancelled) << result.status.message;
}

TEST(Registration, ScanThatRegistersAtOnceIsNotSearchedAgain) {
  // The second search only runs after a failure: a scan that registers gives the same pose and
  // counts whatever retry_candidates says.
  const SyntheticScan truth = makeCase(blade(), caseConfig(2, 0.005, true, 0.0));
  PipelineConfig off;
  off.correspondence.retry_candidates = 0;
  const InspectionResult without = inspect(blade(), truth.scan, off);
  const InspectionResult with = inspect(blade(), truth.scan, PipelineConfig());
  ASSERT_EQ(with.registration, RegistrationStatus::kOk) << with.status.message;
  EXPECT_EQ(without.T_cad_scan.matrix(), with.T_cad_scan.matrix());
  EXPECT_EQ(without.counts.candidates, with.counts.candidates);
  EXPECT_EQ(without.warnings, with.warnings);
}

TEST(Registration, SymmetricPartIsNeverAConfidentWrongPose) {
  // A 100 × 60 × 40 mm box looks the same after 180° turns about its axes: from a full scan no
  // method can tell which turn is right. Either the pose is right, or the result says ambiguous
  // (with the alternatives) — never "ok" with a turned pose.
  const Model box(test::makeBox(Eigen::Vector3d(0.05, 0.03, 0.02)), "box", "test");
  int ambiguous = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const SyntheticScan truth = makeCase(box, caseConfig(seed, 0.002, false, 0.0));
    const InspectionResult result = inspect(box, truth.scan, PipelineConfig());
    const PoseError error = poseError(result, truth, box.bounds().diagonal());
    if (result.registration == RegistrationStatus::kOk) {
      EXPECT_LT(error.rotation_deg, 2.0) << "seed " << seed << ": a turned box reported as ok";
    }
    if (result.registration == RegistrationStatus::kAmbiguous) {
      ++ambiguous;
      EXPECT_FALSE(result.alternatives.empty());
      EXPECT_EQ(result.status.code, StatusCode::kAmbiguous);
      // Its half turns explain the scan as well as the pose does, but for the noise.
      EXPECT_GT(result.ambiguity, 0.95) << "seed " << seed;
      EXPECT_LE(result.ambiguity, 1.0) << "seed " << seed;
    }
    std::printf("box seed %llu: %s, ambiguity %.4f\n",
                static_cast<unsigned long long>(seed),
                toString(result.registration),
                result.ambiguity);
  }
  EXPECT_GE(ambiguous, 1) << "a box must be reported ambiguous at least sometimes";
}

// Whether `pose` places the view's measured points within 2° and 1 % of L of where `truth` does.
bool placesViewLike(const Eigen::Isometry3d& pose, const VirtualScan& view, double diagonal) {
  constexpr double kDegree = 3.14159265358979323846 / 180.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double measured = 0.0;
  for (const auto& p : view.scan.points) {
    if (p.allFinite()) {
      centroid += p;
      measured += 1.0;
    }
  }
  centroid /= std::max(measured, 1.0);
  const double turn =
      Eigen::AngleAxisd(pose.linear().transpose() * view.T_cad_scan.linear()).angle();
  return turn < 2.0 * kDegree &&
         (pose * centroid - view.T_cad_scan * centroid).norm() < 0.01 * diagonal;
}

TEST(Registration, BarSeenByACameraIsNeverAConfidentWrongPose) {
  // A 10 × 20 × 100 mm bar in one VGA range image at 0.1 % noise: turned by half about its long
  // axis, or slid, it lays the same view on itself, so only the right pose may be `ok`. The
  // session-16 code reported views 4 and 9 `ok` turned by 180°: the winning pose was a twin of
  // the quick ranking's best, and its own twin, the truth, was never scored (docs/registration.md,
  // twins of the final pose).
  const Model bar(test::makeBox(Eigen::Vector3d(0.005, 0.01, 0.05)), "bar", "test");
  const double diagonal = bar.bounds().diagonal();
  for (const std::uint64_t seed : {4u, 9u}) {
    VirtualScannerConfig camera;
    camera.seed = seed;
    camera.fill_ratio = 0.8;
    camera.noise_ratio = 0.001;
    const VirtualScan view = makeVirtualScan(bar.query(), camera);
    ASSERT_TRUE(view.status.ok()) << view.status.message;
    const InspectionResult result = inspect(bar, view.scan, PipelineConfig());
    if (result.registration == RegistrationStatus::kOk) {
      EXPECT_TRUE(placesViewLike(result.T_cad_scan, view, diagonal))
          << "view " << seed << ": a turned or slid bar reported as ok";
    } else {
      // Where the view shows neither end, every slid pose fits it: the alternatives need not
      // hold the truth, but there must be some.
      EXPECT_EQ(result.registration, RegistrationStatus::kAmbiguous)
          << "view " << seed << ": " << result.status.message;
      EXPECT_FALSE(result.alternatives.empty()) << "view " << seed;
    }
  }
}

// The same bar as a binary STL from test/data/make_parts.py, triangulated otherwise: views 4 and
// 36 (one long face and one end in view) came back `ok` turned by 180° up to 0.9.6. The final
// pose came from the retries, whose poses about its half turn had drifted along the bar
// (0.83-0.88 of the view explained) and kept its exact twins (0.96, as the pose itself) out of
// the contenders. A box lies on itself under three half turns: every view of it is ambiguous,
// with the truth among the poses.
// A CAD exported coarsely (the pump cover at 16 facets per circle, its 120 mm disc 1.1 mm
// inside the circle between corners) and scans of the real round part (the same cover at 64
// facets). Fitted to the faces, partial views at 0.1 % noise came back `ok` 1.7-1.9° and 0.58 %
// of L off, a hundred times what their noise allows; fitted to the curve the faces stand for
// (chord_error.h), whose share the scan shows, 0.006-0.014° and 0.04 % (checked by building
// without the curve). The deviations stay measured from the faces.
TEST(Registration, CoarseCadIsFittedToTheCurveAScanOfTheRealPartFollows) {
  const auto coarse = load(kCoarsePump, 1.0);
  const MeshLoadResult fine = loadMesh(kFinePump, 1.0);
  ASSERT_TRUE(coarse && fine.status.ok());
  const MeshQuery real_part(fine.mesh);
  const double diagonal = coarse->bounds().diagonal();
  for (const std::uint64_t seed : {1, 2}) {
    SyntheticScanConfig config;
    config.partial = true;
    config.noise_ratio = 0.001;
    config.seed = seed;
    const SyntheticScan truth = makeSyntheticScan(real_part, config);
    ASSERT_TRUE(truth.status.ok());
    const InspectionResult result = inspect(*coarse, truth.scan, PipelineConfig());
    ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
    EXPECT_GT(result.cad_curve_share, 0.5) << "seed " << seed;
    const PoseError error = poseError(result, truth, diagonal);
    EXPECT_LT(error.rotation_deg, 0.2) << "seed " << seed;
    EXPECT_LT(error.centroid_ratio, 0.001) << "seed " << seed;
  }
  // A scan made from the coarse mesh itself follows its faces: no share of the curve.
  SyntheticScanConfig config;
  config.partial = true;
  config.noise_ratio = 0.001;
  const SyntheticScan faces = makeCase(*coarse, config);
  const InspectionResult result = inspect(*coarse, faces.scan, PipelineConfig());
  ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  EXPECT_EQ(result.cad_curve_share, 0.0);
  EXPECT_LT(poseError(result, faces, diagonal).rotation_deg, 0.1);
}

TEST(Registration, BoxBarViewsAreAmbiguousWithTheTruthAmongThePoses) {
  static const auto bar = load(std::string(FREEFORM_TEST_DATA_DIR) + "/meshes/box_bar.stl", 1.0);
  const double diagonal = bar->bounds().diagonal();
  for (const std::uint64_t seed : {4u, 36u}) {
    VirtualScannerConfig camera;
    camera.seed = seed;
    camera.fill_ratio = 0.8;
    camera.noise_ratio = 0.001;
    const VirtualScan view = makeVirtualScan(bar->query(), camera);
    ASSERT_TRUE(view.status.ok()) << view.status.message;
    const InspectionResult result = inspect(*bar, view.scan, PipelineConfig());
    std::printf("view %llu: %s, %zu alternatives\n",
                static_cast<unsigned long long>(seed),
                toString(result.registration),
                result.alternatives.size());
    EXPECT_EQ(result.registration, RegistrationStatus::kAmbiguous)
        << "view " << seed << ": " << result.status.message;
    bool truth_among = placesViewLike(result.T_cad_scan, view, diagonal);
    for (const Eigen::Isometry3d& pose : result.alternatives) {
      truth_among = truth_among || placesViewLike(pose, view, diagonal);
    }
    EXPECT_TRUE(truth_among) << "view " << seed;
  }
}

// Terms of verificationScore() for `count` points: each explained (a term in (0, 1]) with
// probability `explained`, from a fixed seed.
std::vector<double> randomTerms(std::size_t count, double explained, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> terms(count, 0.0);
  for (double& term : terms) {
    term = unit(rng) < explained ? 0.05 + 0.95 * unit(rng) : 0.0;
  }
  return terms;
}

// Terms of two poses over 1,500 points that both explain but for `only_a` points that only
// the first explains and `only_b` that only the second does.
std::pair<std::vector<double>, std::vector<double>> differing(std::size_t only_a,
                                                              std::size_t only_b) {
  std::vector<double> a(1500, 0.5);
  std::vector<double> b(1500, 0.5);
  std::fill_n(b.begin(), only_a, 0.0);
  std::fill_n(a.begin() + static_cast<std::ptrdiff_t>(only_a), only_b, 0.0);
  return {a, b};
}

TEST(Registration, ScanPrefersOnlyAPoseThatExplainsClearlyMore) {
  // Twins of a symmetric part: each explains ~96 % of the 1,500 points, different ones by
  // chance. No seed may make either preferred.
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const std::vector<double> a = randomTerms(1500, 0.96, seed);
    const std::vector<double> b = randomTerms(1500, 0.96, 1000 + seed);
    EXPECT_FALSE(scanPrefers(a, b)) << "seed " << seed;
    EXPECT_FALSE(scanPrefers(b, a)) << "seed " << seed;
  }
  // The same twin with 60 points of a feature only the right pose explains (a flange's bolt
  // holes that are not evenly spaced): 4 % of the scan.
  std::vector<double> right = randomTerms(1500, 0.96, 7);
  std::vector<double> turned = right;
  for (std::size_t i = 0; i < 60; ++i) {
    right[i] = 0.8;
    turned[i] = 0.0;
  }
  EXPECT_TRUE(scanPrefers(right, turned));
  EXPECT_FALSE(scanPrefers(turned, right));
  // Significant as a coin toss (100 against 60: 3.2 σ) but not twice as many: no preference.
  EXPECT_FALSE(scanPrefers(differing(100, 60).first, differing(100, 60).second));
  // Exact twins (a box turned by 180°, both poses refined): nothing to tell them apart.
  EXPECT_FALSE(scanPrefers(differing(0, 0).first, differing(0, 0).second));
  // 14 against none is 3.7 σ, but under 1 % of the 1,500 points: a few stray points.
  EXPECT_FALSE(scanPrefers(differing(14, 0).first, differing(14, 0).second));
  // Twice as many but only 12 against 6 (1.4 σ): chance, no preference.
  EXPECT_FALSE(scanPrefers(differing(12, 6).first, differing(12, 6).second));
  // 30 against none (2 % of the points, 5.5 σ): preferred.
  EXPECT_TRUE(scanPrefers(differing(30, 0).first, differing(30, 0).second));
}

TEST(Registration, ScanLeansIsTheSignTestAlone) {
  // 100 against 60 is 3.2 σ of a coin toss: leans at 2 σ and at 3 σ, though scanPrefers (which
  // wants twice as many) does not decide on it.
  EXPECT_TRUE(scanLeans(differing(100, 60).first, differing(100, 60).second, 2.0));
  EXPECT_TRUE(scanLeans(differing(100, 60).first, differing(100, 60).second, 3.0));
  EXPECT_FALSE(scanLeans(differing(100, 60).second, differing(100, 60).first, 2.0));
  // 12 against 6 is 1.4 σ; 6 against 2 (a flange turned a few degrees, its fitted cells
  // preferring it) 1.4 σ: neither leans at 2 σ. 10 against 2 is 2.3 σ.
  EXPECT_FALSE(scanLeans(differing(12, 6).first, differing(12, 6).second, 2.0));
  EXPECT_FALSE(scanLeans(differing(6, 2).first, differing(6, 2).second, 2.0));
  EXPECT_TRUE(scanLeans(differing(10, 2).first, differing(10, 2).second, 2.0));
  // Nothing either way leans nowhere.
  EXPECT_FALSE(scanLeans(differing(0, 0).first, differing(0, 0).second, 0.0));
  // With a share: 14 of the 1,500 points against none is 3.7 σ but under 1 % (stray cells of a
  // bar's view turned end for end); 15 is 1 %.
  EXPECT_TRUE(scanLeans(differing(14, 0).first, differing(14, 0).second, 2.0));
  EXPECT_FALSE(scanLeans(differing(14, 0).first, differing(14, 0).second, 2.0, 0.01));
  EXPECT_TRUE(scanLeans(differing(15, 0).first, differing(15, 0).second, 2.0, 0.01));
  EXPECT_FALSE(scanLeans(differing(10, 2).first, differing(10, 2).second, 2.0, 0.01));
}

// The fitted verification set: the cells makeVerificationSet takes, each at the mean of its
// points' given positions; a cell without positions keeps its centroid.
TEST(Registration, VerificationSetAtTheMeanOfItsPointsFittedPositions) {
  SurfaceGraph graph;
  graph.centroids = {Eigen::Vector3d(0.0, 0.0, 0.3),
                     Eigen::Vector3d(1.0, 0.0, -0.2),
                     Eigen::Vector3d(2.0, 0.0, 0.1)};
  graph.normals.assign(3, Eigen::Vector3d::UnitZ());
  graph.point_cell = {0, 0, 1, 1, 1, -1};
  const Points positions = {Eigen::Vector3d(-0.1, 0.0, 0.0),
                            Eigen::Vector3d(0.1, 0.0, 0.0),
                            Eigen::Vector3d(0.9, 0.0, 0.0),
                            Eigen::Vector3d(1.0, 0.0, 0.0),
                            Eigen::Vector3d(1.1, 0.0, 0.03),
                            Eigen::Vector3d(5.0, 5.0, 5.0)};
  const VerificationSet plain = makeVerificationSet(graph, 3, true);
  const VerificationSet fitted = makeVerificationSet(graph, 3, true, positions);
  ASSERT_EQ(fitted.points.size(), 3u);
  EXPECT_TRUE(fitted.oriented);
  EXPECT_LT((fitted.points[0] - Eigen::Vector3d(0.0, 0.0, 0.0)).norm(), 1e-12);
  EXPECT_LT((fitted.points[1] - Eigen::Vector3d(1.0, 0.0, 0.01)).norm(), 1e-12);
  EXPECT_LT((fitted.points[2] - graph.centroids[2]).norm(), 1e-12);  // no points of its own
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_LT((fitted.normals[i] - plain.normals[i]).norm(), 1e-12);
  }
  // Two of three cells: the same cells as the plain set (0 and 1).
  const VerificationSet two = makeVerificationSet(graph, 2, false, positions);
  ASSERT_EQ(two.points.size(), 2u);
  EXPECT_LT((two.points[1] - Eigen::Vector3d(1.0, 0.0, 0.01)).norm(), 1e-12);
}

// Partial views of the cast KUKA link at 2 % noise (σ = 5.5 mm), 30,000 points as in
// bench/registration_eval: its half turn explained nearly as much of the noisy cells' centroids
// (points only the right pose explained outnumbered the turn's by 1.5-2 to 1), so seeds 1 and 2
// came back ambiguous. On the cells' fitted positions the right pose is told apart
// (registration.md, "Rivals weighed on the fitted surfaces"). Before, 1 of these 3 was ok.
TEST(Registration, NoisyPartialViewsOfACastLinkToldFromTheirHalfTurns) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto [result, error] = registerCase(link(), seed, 0.02, true);
    ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
    EXPECT_LT(error.rotation_deg, 2.0);
    EXPECT_LT(error.centroid_ratio, 0.01);
  }
}

// A tube with round ends seen whole at 2 % noise (the UR10e forearm, σ = 14 mm): the view fixes
// its turn about the tube's axis only weakly, and the quick refinement of the hypotheses stops
// 10-13° along that turn, where the pose explains the scan about as well as the best (0.997
// against 0.998). Refined to convergence such a rival comes back onto the best pose (within
// 1-3°): one pose, not two, so the result is ok (seeds 5 and 9: ambiguous with that rival until
// 0.9.8). Its half turn, the tube end for end, stays a rival: seed 8 is ambiguous with the twin
// among its alternatives.
TEST(Registration, RivalsInTheBestPosesBasinAreNoAlternatives) {
  static const auto forearm = load(kForearm, 1.0);
  for (const std::uint64_t seed : {5, 9, 8}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto [result, error] = registerCase(*forearm, seed, 0.02, false);
    EXPECT_LT(error.rotation_deg, 2.0);
    EXPECT_LT(error.centroid_ratio, 0.01);
    if (seed != 8) {
      EXPECT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
      continue;
    }
    ASSERT_EQ(result.registration, RegistrationStatus::kAmbiguous) << result.status.message;
    double widest_deg = 0.0;
    for (const Eigen::Isometry3d& alternative : result.alternatives) {
      widest_deg = std::max(
          widest_deg,
          Eigen::AngleAxisd(alternative.linear().transpose() * result.T_cad_scan.linear()).angle() *
              180.0 / M_PI);
    }
    EXPECT_GT(widest_deg, 170.0);
  }
}

// The guard of that test: the flange seen from one side at 0.5 % noise (seed 1) comes out of ICP
// turned 7.6° about its axis, the truth among no contenders, and on the fitted cells that pose
// beats each of its other turns (27-63 points to 2-11). The centroids lean its way at 2 σ
// against only some of them (most read 3-6 points to 1-3), so the others stay rivals:
// ambiguous, not a turned flange reported ok (without the lean: ok, 7.6° off).
TEST(Registration, FittedCellsDismissNoRivalTheCentroidsDoNotLeanAgainst) {
  static const auto flange = load(kFlange, 1.0);
  SyntheticScanConfig config = caseConfig(1, 0.005, true, 0.0);
  config.points = 30000;
  const SyntheticScan truth = makeCase(*flange, config);
  const InspectionResult result = inspect(*flange, truth.scan, PipelineConfig());
  const PoseError error = poseError(result, truth, flange->bounds().diagonal());
  std::printf("flange: %s, %.3f deg, %.4f L, %zu alternatives\n",
              toString(result.registration),
              error.rotation_deg,
              error.centroid_ratio,
              result.alternatives.size());
  if (result.registration == RegistrationStatus::kOk) {
    EXPECT_LT(error.rotation_deg, 2.0);
    EXPECT_LT(error.centroid_ratio, 0.01);
  } else {
    EXPECT_EQ(result.registration, RegistrationStatus::kAmbiguous) << result.status.message;
    EXPECT_FALSE(result.alternatives.empty());
  }
}

TEST(Registration, VerificationCountsNoisyPointsOnAWallThinnerThanTheNoise) {
  // A wall 1 mm thick seen from both sides with σ = 0.5 mm along the normals, printed seed: a
  // point pushed past the mid-plane is nearer the far face, which faces the other way. It is
  // still explained, by its own face within the 3σ truncation.
  constexpr unsigned kSeed = 20261123;
  constexpr double kSigma = 0.0005;  // [m]
  const MeshQuery wall(test::makeBox(Eigen::Vector3d(0.01, 0.01, 0.0005)));
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> across(-0.009, 0.009);
  std::normal_distribution<double> noise(0.0, kSigma);
  VerificationSet set;
  set.oriented = true;
  for (int i = 0; i < 1500; ++i) {
    const double side = i % 2 == 0 ? 1.0 : -1.0;
    set.points.emplace_back(across(rng), across(rng), side * 0.0005 + noise(rng));
    set.normals.emplace_back(0.0, 0.0, side);
  }
  const double truncation = 3.0 * kSigma;
  const auto explained = [&](const Eigen::Isometry3d& pose) {
    const std::vector<double> terms = verificationTerms(pose, set, wall, truncation, 40.0);
    return static_cast<double>(
               std::count_if(terms.begin(), terms.end(), [](double t) { return t > 0.0; })) /
           static_cast<double>(terms.size());
  };
  EXPECT_GT(explained(Eigen::Isometry3d::Identity()), 0.98) << "seed " << kSeed;
  // The nearest face alone would disown the ~16 % pushed past the mid-plane (noise beyond 1σ).
  int nearest_agrees = 0;
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    nearest_agrees += wall.closest(set.points[i], truncation).normal.dot(set.normals[i]) > 0.0;
  }
  EXPECT_LT(nearest_agrees, 0.9 * 1500);
  // Moved 3 mm off the wall, the points are explained by nothing.
  EXPECT_LT(explained(Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, 0.003))), 0.01);
}

TEST(Registration, HypothesesThatCannotRankAmongTheRefinedAreDroppedWithTheBestExact) {
  // The blade registered to itself, as the symmetry search does: its hypotheses verified in
  // full, then with only the best 12 needing exact scores.
  const Model& model = blade();
  const DescriptorResult& cad = model.descriptors();
  const FeatureResult features =
      selectFeatures(cad.graph.centroids, cad.cell_values, cad.radii.back(), FeatureConfig());
  const CorrespondenceResult candidates = findCandidates(cad.cell_values,
                                                         features.cells,
                                                         cad.cell_values,
                                                         cad.graph.centroids,
                                                         model.cellSize(),
                                                         CorrespondenceConfig());
  GlobalRegistrationConfig config;
  config.max_fits = 20000;
  config.verification_points = 600;
  const auto run = [&](int refined) {
    config.refined_hypotheses = refined;
    return registerGlobally(cad.graph,
                            cad.graph,
                            candidates,
                            model.query(),
                            model.cellSize(),
                            cad.radii.back(),
                            config,
                            true);
  };
  const GlobalRegistrationResult full = run(config.verified_hypotheses);
  const GlobalRegistrationResult ranked = run(12);
  ASSERT_TRUE(full.status.ok()) << full.status.message;
  ASSERT_EQ(static_cast<int>(full.hypotheses.size()), config.verified_hypotheses);
  ASSERT_GE(ranked.hypotheses.size(), 12u);
  EXPECT_LT(ranked.hypotheses.size(), full.hypotheses.size()) << "nothing was dropped";
  for (std::size_t h = 0; h < 12; ++h) {
    EXPECT_EQ(ranked.hypotheses[h].score, full.hypotheses[h].score) << h;
    EXPECT_TRUE(ranked.hypotheses[h].T_cad_scan.isApprox(full.hypotheses[h].T_cad_scan, 0.0)) << h;
  }
  // Everything dropped scored below the 12th best.
  const double twelfth = full.hypotheses[11].score;
  std::size_t below = 0;
  for (const PoseHypothesis& h : full.hypotheses) {
    below += h.score < twelfth ? 1 : 0;
  }
  EXPECT_GE(below, full.hypotheses.size() - ranked.hypotheses.size());

  // The floor: met, the exact score; missed, a bound between the score and the floor.
  const VerificationSet set = makeVerificationSet(cad.graph, 600, true);
  const double truncation = config.verification_distance_cells * model.cellSize();
  const Eigen::Isometry3d pose = full.hypotheses[20].T_cad_scan;
  const double score = verificationScore(pose, set, model.query(), truncation, 40.0);
  ASSERT_GT(score, 0.05);
  ASSERT_LT(score, 0.95);
  EXPECT_EQ(verificationScore(pose, set, model.query(), truncation, 40.0, score), score);
  const double bound = verificationScore(pose, set, model.query(), truncation, 40.0, score + 0.05);
  EXPECT_LT(bound, score + 0.05);
  EXPECT_GE(bound, score);
}

TEST(Registration, PosesAreListedApartBeyondTenDegreesOrThreeCells) {
  constexpr double kDegree = 3.14159265358979323846 / 180.0;
  const double cell = 0.002;  // [m]
  const Eigen::Vector3d reference(0.3, -0.1, 0.5);
  const Eigen::Isometry3d pose = Eigen::Translation3d(0.05, 0.2, -0.4) *
                                 Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  // Turned about the reference (it does not move): only the angle counts.
  const auto turned = [&](double degrees) {
    const Eigen::Vector3d at = pose * reference;
    return Eigen::Translation3d(at) *
           Eigen::AngleAxisd(degrees * kDegree, Eigen::Vector3d::UnitZ()) *
           Eigen::Translation3d(-at) * pose;
  };
  EXPECT_FALSE(separatePoses(pose, turned(9.9), reference, cell));
  EXPECT_TRUE(separatePoses(pose, turned(10.1), reference, cell));
  EXPECT_TRUE(separatePoses(turned(-10.1), pose, reference, cell));
  // Shifted without turning: only the reference's displacement counts.
  const auto shifted = [&](double cells) {
    return Eigen::Translation3d(Eigen::Vector3d(0.0, cells * cell, 0.0)) * pose;
  };
  EXPECT_FALSE(separatePoses(pose, shifted(2.9), reference, cell));
  EXPECT_TRUE(separatePoses(pose, shifted(3.1), reference, cell));
  EXPECT_FALSE(separatePoses(pose, pose, reference, cell));
  // poseGap() counts in those units: the larger of turn / 10° and shift / 3 cells.
  EXPECT_NEAR(poseGap(pose, turned(5.0), reference, cell), 0.5, 1e-9);
  EXPECT_NEAR(poseGap(turned(-25.0), pose, reference, cell), 2.5, 1e-9);
  EXPECT_NEAR(poseGap(pose, shifted(1.5), reference, cell), 0.5, 1e-9);
  const Eigen::Isometry3d both = Eigen::Translation3d(0.0, 1.5 * cell, 0.0) * turned(20.0);
  EXPECT_NEAR(poseGap(pose, both, reference, cell), 2.0, 1e-9);
  EXPECT_EQ(poseGap(pose, pose, reference, cell), 0.0);
  // A rival comes onto the best when refinement brings it within that separation and closes at
  // least the given share of its gap: 12° → 1° yes; 10.5° → 9.5° (on the line, barely moved) and
  // 12° → 7° (within 10°, but 42 % of the way) no; 25° → 12° never (still apart).
  EXPECT_TRUE(refinedOnto(pose, turned(12.0), turned(1.0), reference, cell, 0.5));
  EXPECT_FALSE(refinedOnto(pose, turned(10.5), turned(9.5), reference, cell, 0.5));
  EXPECT_FALSE(refinedOnto(pose, turned(12.0), turned(7.0), reference, cell, 0.5));
  EXPECT_TRUE(refinedOnto(pose, turned(12.0), turned(5.0), reference, cell, 0.5));
  EXPECT_FALSE(refinedOnto(pose, turned(25.0), turned(12.0), reference, cell, 0.5));
}

TEST(Registration, NearSymmetricFlangeIsToldApartWhenTheScanShowsTheDifference) {
  // The ABB flange turned by 120° lies on itself but for 8 % of its surface. A full scan shows
  // that part, and where it clearly sides with one pose that pose is "ok"; where it does not,
  // the result stays ambiguous. Never "ok" with a turned pose: seed 13 is a partial view at 1 %
  // that was reported "ok" turned by 119.5° until the rivals' gate compared like with like and
  // the evidence stopped counting the noise on thin walls (docs/registration.md); it is now
  // ambiguous.
  const auto flange = load(kFlange, 1.0);
  ASSERT_TRUE(flange);
  int ok = 0;
  for (const std::uint64_t seed : {1, 2, 3, 13}) {
    const bool partial = seed == 13;
    SyntheticScanConfig config = caseConfig(seed, partial ? 0.01 : 0.005, partial, 0.0);
    config.points = partial ? 30000 : config.points;  // as registration_eval made that view
    const SyntheticScan truth = makeCase(*flange, config);
    const InspectionResult result = inspect(*flange, truth.scan, PipelineConfig());
    const PoseError error = poseError(result, truth, flange->bounds().diagonal());
    std::printf("flange seed %d: %s, %.2f deg\n",
                static_cast<int>(seed),
                toString(result.registration),
                error.rotation_deg);
    // Every stage is timed, the rivals' refinement included: the stages add up to the total
    // (what is left is bookkeeping between stages).
    double stages = 0.0;
    for (std::size_t t = 0; t + 1 < result.timings.size(); ++t) {
      stages += result.timings[t].seconds;
    }
    ASSERT_FALSE(result.timings.empty());
    EXPECT_NEAR(stages, result.timings.back().seconds, 0.02 + 0.02 * result.timings.back().seconds)
        << "seed " << seed;
    if (result.registration == RegistrationStatus::kOk) {
      ++ok;
      EXPECT_LT(error.rotation_deg, 2.0) << "seed " << seed << ": a turned flange reported as ok";
      EXPECT_LT(error.centroid_ratio, 0.01) << "seed " << seed;
    } else {
      EXPECT_EQ(result.registration, RegistrationStatus::kAmbiguous) << result.status.message;
    }
  }
  // The three full views show the uneven bolt holes (until session 10 two of them said so; since
  // the evidence counts surfaces facing each point's way, all three).
  EXPECT_EQ(ok, 3) << "the full views show the flange's asymmetry: each must say so";
}

TEST(Registration, ScanOfAnotherPartIsNotRegistered) {
  // The cast link scanned, the blade as CAD: a different part must not come back as "ok".
  SyntheticScanConfig config = caseConfig(10, 0.002, false, 0.0);
  const SyntheticScan other = makeCase(link(), config);
  // Scale the link's scan to the blade's size so the units check lets it through.
  Scan scan = other.scan;
  const double ratio = blade().bounds().diagonal() / link().bounds().diagonal();
  for (auto& p : scan.points) {
    p *= ratio;
  }
  const InspectionResult result = inspect(blade(), scan, PipelineConfig());
  EXPECT_EQ(result.registration, RegistrationStatus::kFailed)
      << "score " << result.score << ", fitness " << result.fitness;
  // It failed after the second, wider candidate search too, and says so.
  EXPECT_TRUE(std::any_of(result.warnings.begin(), result.warnings.end(), [](const auto& w) {
    return w.find("correspondence.retry_candidates") != std::string::npos;
  })) << result.status.message;
}

// The generated blade scan with a table under the part: a flat patch 2 mm beyond the CAD box
// across its thinnest axis, covering `share` of the box's largest face, sampled as densely as
// the scan.
Scan withTable(const SyntheticScan& truth, const Model& model, double share, unsigned seed) {
  const BoundingBox box = model.bounds();
  Eigen::Index normal_axis = 0;
  box.extent().minCoeff(&normal_axis);
  const Eigen::Index u = (normal_axis + 1) % 3;
  const Eigen::Index v = (normal_axis + 2) % 3;
  const Eigen::Vector3d centre = 0.5 * (box.min + box.max);
  const double side = std::sqrt(share);
  const double area = side * side * box.extent()[u] * box.extent()[v];
  const auto count = static_cast<int>(area / 5e-7);  // ~2 points per mm², as the scan
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-0.5, 0.5);
  const Eigen::Isometry3d T_scan_cad = truth.T_cad_scan.inverse();
  Scan scan = truth.scan;
  scan.normals.clear();
  for (int i = 0; i < count; ++i) {
    Eigen::Vector3d p = centre;
    p[u] += side * box.extent()[u] * unit(rng);
    p[v] += side * box.extent()[v] * unit(rng);
    p[normal_axis] = box.min[normal_axis] - 0.002;
    scan.points.push_back(T_scan_cad * p);
  }
  return scan;
}

TEST(Registration, ForeignSurfaceIsRefusedUnlessTheLimitAllowsIt) {
  // A table under the blade is surface that the CAD does not have: by default a pose that
  // leaves more than 20 % of the scan's surface off the CAD is not trusted (it is what a flipped
  // or slid pose looks like); the integrator who cannot crop lowers the limit.
  SyntheticScanConfig config = caseConfig(12, 0.002, false, 0.0);
  config.points = 30000;
  const SyntheticScan truth = makeCase(blade(), config);
  const Scan scan = withTable(truth, blade(), 1.0, 12);  // ~a third of the surface
  const InspectionResult refused = inspect(blade(), scan, PipelineConfig());
  EXPECT_EQ(refused.registration, RegistrationStatus::kFailed);
  EXPECT_NE(refused.status.message.find("registration.min_surface_on_cad"), std::string::npos)
      << refused.status.message;
  EXPECT_LT(refused.surface_on_cad, 0.8);
  PipelineConfig allowing;
  allowing.registration.min_surface_on_cad = 0.4;
  const InspectionResult result = inspect(blade(), scan, allowing);
  ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  const PoseError error = poseError(result, truth, blade().bounds().diagonal());
  EXPECT_LT(error.rotation_deg, 2.0);
  EXPECT_LT(error.centroid_ratio, 0.01);
  EXPECT_GT(result.surface_on_cad, 0.4);
}

}  // namespace
}  // namespace freeform_inspection
