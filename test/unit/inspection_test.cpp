// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// The verdict on the shipped blade: generated scans at random poses (synthetic_scan.h), clean
// or with a spherical-cap dent of known place and depth pressed into them (surface_defect.h).
// Noise σ is a share of the CAD diagonal L; tolerances are multiples of σ.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/deviation.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/pipeline.h"
#include "freeform_inspection/surface_defect.h"
#include "freeform_inspection/synthetic_scan.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;
const std::string kBlade = std::string(FREEFORM_DATA_DIR) + "/blade/blade.stl";

const Model& blade() {
  static const auto model = [] {
    const ModelLoadResult loaded = loadModel(kBlade, 0.001, "blade");
    EXPECT_TRUE(loaded.status.ok()) << loaded.status.message;
    return loaded.model;
  }();
  return *model;
}

double diagonal() {
  return blade().bounds().diagonal();
}

SyntheticScan makeCase(std::uint64_t seed, double noise_ratio, bool partial) {
  SyntheticScanConfig config;
  config.seed = seed;
  config.noise_ratio = noise_ratio;
  config.partial = partial;
  const SyntheticScan truth = makeSyntheticScan(blade().query(), config);
  EXPECT_TRUE(truth.status.ok()) << truth.status.message;
  std::printf("seed %llu, noise %.2f %% of L, %s view\n",
              static_cast<unsigned long long>(seed),
              noise_ratio * 100.0,
              partial ? "partial" : "full");
  return truth;
}

PipelineConfig withBand(double half_width) {
  PipelineConfig config;
  config.tolerance.upper = half_width;
  config.tolerance.lower = -half_width;
  return config;
}

// A dent on the blade's broad face, under the scan point nearest the scan's centroid, with a
// base radius that covers `area_share` of the CAD surface. Returns it in the CAD frame.
SurfaceDefect pressDent(SyntheticScan* truth, double area_share, double depth) {
  const MeshQuery& cad = blade().query();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : truth->scan.points) {
    centroid += p / static_cast<double>(truth->scan.points.size());
  }
  std::size_t nearest = 0;
  for (std::size_t i = 0; i < truth->scan.points.size(); ++i) {
    if ((truth->scan.points[i] - centroid).squaredNorm() <
        (truth->scan.points[nearest] - centroid).squaredNorm()) {
      nearest = i;
    }
  }
  SurfaceDefect dent;
  dent.centre = cad.closest(truth->T_cad_scan * truth->scan.points[nearest]).point;
  dent.radius = std::sqrt(area_share * blade().topology().area / kPi);
  dent.depth = depth;
  EXPECT_GT(pressDefect(cad, dent, truth), 0u);
  return dent;
}

double rotationDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / kPi;
}

TEST(Inspection, CleanBladePassesAtAFourSigmaBand) {
  const double sigma = 0.005 * diagonal();
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    const SyntheticScan truth = makeCase(seed, 0.005, false);
    const InspectionResult result = inspect(blade(), truth.scan, withBand(4.0 * sigma));
    const DeviationStatistics& s = result.deviation;
    std::printf(
        "  %s: %s; std %.3g sigma, mean %.3g sigma, in band %.4f, coverage %.3f, "
        "%zu defects\n",
        toString(result.verdict),
        result.verdict_reason.c_str(),
        s.std / sigma,
        s.mean / sigma,
        s.in_tolerance_fraction,
        s.coverage,
        result.defects.size());
    ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
    EXPECT_EQ(result.verdict, Verdict::kPass) << result.verdict_reason;
    EXPECT_TRUE(result.defects.empty());
    EXPECT_NEAR(s.std, sigma, 0.15 * sigma);
    EXPECT_NEAR(s.mean, 0.0, 0.2 * sigma);
    EXPECT_GT(s.in_tolerance_fraction, 0.999);
    EXPECT_GT(s.coverage, 0.95);
    EXPECT_EQ(result.deviation_map.size(), result.counts.scan_points);
    EXPECT_EQ(s.evaluated + s.unmatched, result.counts.scan_points);
  }
}

TEST(Inspection, DentIsFoundInPlaceAndDoesNotPullThePose) {
  const double sigma = 0.0005 * diagonal();
  const double depth = -20.0 * sigma;
  for (std::uint64_t seed = 3; seed <= 4; ++seed) {
    const SyntheticScan clean = makeCase(seed, 0.0005, false);
    SyntheticScan dented = clean;
    const SurfaceDefect dent = pressDent(&dented, 0.05, depth);
    const PipelineConfig config = withBand(4.0 * sigma);
    const InspectionResult reference = inspect(blade(), clean.scan, config);
    const InspectionResult result = inspect(blade(), dented.scan, config);
    ASSERT_EQ(reference.registration, RegistrationStatus::kOk) << reference.status.message;
    ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
    ASSERT_FALSE(result.defects.empty());
    const DefectRegion& found = result.defects.front();
    // The pose moved by the dent, measured where the scan is: rotation and centroid shift.
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& p : clean.scan.points) {
      centroid += p / static_cast<double>(clean.scan.points.size());
    }
    const double shift =
        (result.T_cad_scan * centroid - reference.T_cad_scan * centroid).norm() / diagonal();
    const double turn = rotationDeg(result.T_cad_scan, reference.T_cad_scan);
    std::printf(
        "  dent r %.3g mm, depth %.3g mm: found %s peak %.3g mm at %.3g mm from the "
        "centre, %zu regions; pose moved %.4f deg, %.5f L\n",
        dent.radius * 1e3,
        depth * 1e3,
        found.sign < 0 ? "dent" : "bump",
        found.peak * 1e3,
        (found.centroid - dent.centre).norm() * 1e3,
        result.defects.size(),
        turn,
        shift);
    EXPECT_EQ(result.verdict, Verdict::kFail);
    EXPECT_EQ(result.defects.size(), 1u);  // one dent, one region
    EXPECT_EQ(found.sign, -1);
    EXPECT_LT((found.centroid - dent.centre).norm(), dent.radius);
    EXPECT_NEAR(found.peak, depth, 0.2 * std::abs(depth));
    EXPECT_LT(turn, 0.05);
    EXPECT_LT(shift, 0.0005);
    EXPECT_EQ(reference.verdict, Verdict::kPass) << reference.verdict_reason;
  }
}

TEST(Inspection, ShapeDeviationHighlightsTheDent) {
  const double sigma = 0.001 * diagonal();
  SyntheticScan dented = makeCase(5, 0.001, false);
  const SurfaceDefect dent = pressDent(&dented, 0.05, -20.0 * sigma);
  const InspectionResult result = inspect(blade(), dented.scan, withBand(4.0 * sigma));
  ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  const DeviationMap& map = result.deviation_map;
  double inside = 0.0;
  double outside = 0.0;
  std::size_t n_inside = 0;
  std::size_t n_outside = 0;
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (!std::isfinite(map.shape_deviation[i])) {
      continue;
    }
    const double from_centre = (map.points[i] - dent.centre).norm();
    if (from_centre < 0.5 * dent.radius) {
      inside += map.shape_deviation[i];
      ++n_inside;
    } else if (from_centre > 2.0 * dent.radius) {
      outside += map.shape_deviation[i];
      ++n_outside;
    }
  }
  ASSERT_GT(n_inside, 0u);
  ASSERT_GT(n_outside, 0u);
  std::printf("shape deviation: %.4f in the dent, %.4f away from it (p95 %.4f)\n",
              inside / n_inside,
              outside / n_outside,
              result.deviation.shape_p95);
  EXPECT_GT(inside / n_inside, 2.0 * outside / n_outside);
}

TEST(Inspection, VerdictNeedsATrustedPoseAndEnoughCoverage) {
  // Partial view: judged by default, NOT_EVALUATED when full coverage is demanded.
  const SyntheticScan partial = makeCase(6, 0.002, true);
  PipelineConfig config = withBand(4.0 * 0.002 * diagonal());
  const InspectionResult judged = inspect(blade(), partial.scan, config);
  ASSERT_EQ(judged.registration, RegistrationStatus::kOk) << judged.status.message;
  EXPECT_EQ(judged.verdict, Verdict::kPass) << judged.verdict_reason;
  EXPECT_LT(judged.deviation.coverage, 0.8);
  config.verdict.min_coverage = 0.9;
  const InspectionResult refused = inspect(blade(), partial.scan, config);
  EXPECT_EQ(refused.verdict, Verdict::kNotEvaluated);
  EXPECT_NE(refused.verdict_reason.find("min_coverage"), std::string::npos);

  // A box is symmetric: an ambiguous pose is never judged, though its deviation is shown.
  const Model box(test::makeBox(Eigen::Vector3d(0.05, 0.03, 0.02)), "box", "test");
  SyntheticScanConfig box_case;
  box_case.seed = 2;
  box_case.noise_ratio = 0.002;
  const SyntheticScan boxed = makeSyntheticScan(box.query(), box_case);
  const InspectionResult box_result = inspect(box, boxed.scan, PipelineConfig());
  if (box_result.registration != RegistrationStatus::kOk) {
    EXPECT_EQ(box_result.verdict, Verdict::kNotEvaluated) << box_result.verdict_reason;
  }
  if (box_result.registration == RegistrationStatus::kAmbiguous) {
    EXPECT_GT(box_result.deviation.evaluated, 0u);
  }

  // A scan the CAD cannot explain: NOT_EVALUATED, no deviation.
  Scan flat;
  for (int i = 0; i < 100; ++i) {
    for (int j = 0; j < 100; ++j) {
      flat.points.emplace_back(0.002 * i, 0.002 * j, 0.0005 * std::sin(0.3 * i));
    }
  }
  const InspectionResult failed = inspect(blade(), flat, PipelineConfig());
  EXPECT_EQ(failed.verdict, Verdict::kNotEvaluated);
  EXPECT_TRUE(failed.deviation_map.points.empty());
  EXPECT_FALSE(failed.verdict_reason.empty());
}

// Named regions (regions.h) on a dented blade, judged at its true pose so that only the
// verdict is under test: a region left out hides the dent, a region with a wider band of its
// own passes it, a region with the part's band fails with the dent named in it, and a region the
// scan does not cover as asked leaves the part not evaluated.
TEST(Inspection, NamedRegionsAreJudgedWithTheirOwnBands) {
  const double sigma = 0.001 * diagonal();
  SyntheticScan dented = makeCase(3, 0.001, false);
  const SurfaceDefect dent = pressDent(&dented, 0.03, -20.0 * sigma);
  const auto inspectWith = [&](const std::vector<RegionConfig>& regions) {
    PipelineConfig config = withBand(4.0 * sigma);
    config.regions = regions;
    return inspectAt(blade(), dented.scan, dented.T_cad_scan, config);
  };
  RegionConfig around;
  around.name = "dent";
  const Eigen::Vector3d reach = Eigen::Vector3d::Constant(1.5 * dent.radius);
  around.boxes.push_back({dent.centre - reach, dent.centre + reach});

  const InspectionResult plain = inspectWith({});
  ASSERT_EQ(plain.verdict, Verdict::kFail) << plain.verdict_reason;
  ASSERT_EQ(plain.defects.size(), 1u);
  EXPECT_EQ(plain.defects[0].region, -1);
  EXPECT_TRUE(plain.regions.empty());
  EXPECT_TRUE(plain.deviation_map.region.empty());
  EXPECT_EQ(plain.deviation.excluded, 0u);

  // The part's band in the region: the same defect, now named in it.
  const InspectionResult named = inspectWith({around});
  EXPECT_EQ(named.verdict, Verdict::kFail);
  EXPECT_NE(named.verdict_reason.find("in region 'dent'"), std::string::npos)
      << named.verdict_reason;
  ASSERT_EQ(named.defects.size(), 1u);
  EXPECT_EQ(named.defects[0].region, 0);
  EXPECT_EQ(named.defects[0].points, plain.defects[0].points);
  ASSERT_EQ(named.regions.size(), 1u);
  const RegionResult& region = named.regions[0];
  EXPECT_EQ(region.verdict, Verdict::kFail);
  EXPECT_EQ(region.defects, 1u);
  EXPECT_EQ(region.deviation.min, plain.deviation.min);  // the dent's deepest point is in it
  EXPECT_LT(region.deviation.min, -12.0 * sigma);
  EXPECT_GT(region.deviation.coverage, 0.9);
  EXPECT_EQ(named.deviation.evaluated, plain.deviation.evaluated);
  std::size_t inside = 0;
  for (const int r : named.deviation_map.region) {
    inside += r == 0 ? 1 : 0;
  }
  EXPECT_EQ(region.deviation.evaluated, inside);
  EXPECT_GT(inside, plain.defects[0].points);

  // A band of its own wide enough for the dent: the region and the part pass.
  RegionConfig wide = around;
  wide.has_tolerance = true;
  wide.tolerance = {30.0 * sigma, -30.0 * sigma};
  const InspectionResult passed = inspectWith({wide});
  EXPECT_EQ(passed.verdict, Verdict::kPass) << passed.verdict_reason;
  EXPECT_TRUE(passed.defects.empty());
  ASSERT_EQ(passed.regions.size(), 1u);
  EXPECT_EQ(passed.regions[0].verdict, Verdict::kPass) << passed.regions[0].verdict_reason;
  EXPECT_EQ(passed.regions[0].tolerance.lower, -30.0 * sigma);
  EXPECT_EQ(passed.regions[0].deviation.in_tolerance_fraction, 1.0);
  // With a measurement uncertainty U = 5 σ and the part at ±20 σ, the dent (below -12 σ) lies
  // outside the part's acceptance zone (±15 σ) but inside the region's (±25 σ): the region's
  // band is narrowed by U, not the part's, and the part is proven to conform.
  PipelineConfig guarded = withBand(20.0 * sigma);
  guarded.verdict.measurement_uncertainty = 5.0 * sigma;
  const InspectionResult unproven = inspectAt(blade(), dented.scan, dented.T_cad_scan, guarded);
  EXPECT_EQ(unproven.verdict, Verdict::kNotEvaluated) << unproven.verdict_reason;
  guarded.regions = {wide};
  const InspectionResult proven = inspectAt(blade(), dented.scan, dented.T_cad_scan, guarded);
  EXPECT_EQ(proven.verdict, Verdict::kPass) << proven.verdict_reason;
  ASSERT_EQ(proven.regions.size(), 1u);
  EXPECT_EQ(proven.regions[0].verdict, Verdict::kPass) << proven.regions[0].verdict_reason;
  EXPECT_EQ(proven.regions[0].defects_outside_acceptance, 0u);

  // Left out: measured and shown, judged nowhere.
  RegionConfig left_out = around;
  left_out.evaluate = false;
  const InspectionResult hidden = inspectWith({left_out});
  EXPECT_EQ(hidden.verdict, Verdict::kPass) << hidden.verdict_reason;
  EXPECT_TRUE(hidden.defects.empty());
  EXPECT_EQ(hidden.deviation.excluded, inside);
  EXPECT_EQ(hidden.deviation.evaluated + hidden.deviation.unmatched + hidden.deviation.excluded,
            hidden.counts.scan_points);
  EXPECT_GT(hidden.deviation.min, -8.0 * sigma);  // the dent is not in the statistics
  ASSERT_EQ(hidden.regions.size(), 1u);
  EXPECT_EQ(hidden.regions[0].verdict, Verdict::kNotEvaluated);
  EXPECT_EQ(hidden.regions[0].deviation.evaluated, inside);  // but it is in the region's
  EXPECT_EQ(hidden.regions[0].deviation.min, plain.deviation.min);

  // A region the scan never reaches: not evaluated itself; the part too once it asks for cover.
  RegionConfig elsewhere;
  elsewhere.name = "elsewhere";
  elsewhere.boxes.push_back({Eigen::Vector3d::Constant(10.0), Eigen::Vector3d::Constant(11.0)});
  const InspectionResult unseen = inspectWith({left_out, elsewhere});
  EXPECT_EQ(unseen.verdict, Verdict::kPass) << unseen.verdict_reason;
  EXPECT_EQ(unseen.regions[1].verdict, Verdict::kNotEvaluated);
  EXPECT_NE(unseen.regions[1].verdict_reason.find("no scan point"), std::string::npos);
  elsewhere.min_coverage = 0.5;
  const InspectionResult uncovered = inspectWith({left_out, elsewhere});
  EXPECT_EQ(uncovered.verdict, Verdict::kNotEvaluated);
  EXPECT_NE(uncovered.verdict_reason.find("region 'elsewhere'"), std::string::npos)
      << uncovered.verdict_reason;
}

// Comparison points (comparison_points.h) on a dented blade, registered from scratch: one at the
// dent's centre reads its depth, one on the same face 3 dent radii away reads about nothing, and
// each is judged against its own band; a point outside its band fails a part that would pass,
// one the scan does not show (placed 1000x too far: millimetres read as metres) leaves it not
// evaluated; a scan that does not register reports every point, not evaluated.
TEST(Inspection, ComparisonPointsReadTheDeviationWhereTheyLie) {
  const double sigma = 0.0005 * diagonal();
  const double depth = -20.0 * sigma;
  SyntheticScan dented = makeCase(3, 0.0005, false);
  const SurfaceDefect dent = pressDent(&dented, 0.03, depth);
  // A place on the dented face three dent radii from its centre, where the scan has points.
  const Eigen::Vector3d facing = blade().query().closest(dent.centre).normal;
  Eigen::Vector3d away = dent.centre;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : dented.scan.points) {
    const ClosestPoint on = blade().query().closest(dented.T_cad_scan * p);
    const double off = std::abs((on.point - dent.centre).norm() - 3.0 * dent.radius);
    if (on.normal.dot(facing) > 0.9 && off < best) {
      best = off;
      away = on.point;
    }
  }
  ComparisonPointConfig at_dent;
  at_dent.name = "dent";
  at_dent.position = dent.centre;
  at_dent.radius = 0.2 * dent.radius;
  ComparisonPointConfig beside;
  beside.name = "beside";
  beside.position = away;
  beside.has_tolerance = true;
  beside.tolerance = {2.0 * sigma, -2.0 * sigma};

  PipelineConfig config = withBand(30.0 * sigma);  // the dent passes the surface's band
  config.comparison_points = {at_dent, beside};
  const InspectionResult result = inspect(blade(), dented.scan, config);
  ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  ASSERT_EQ(result.comparison_points.size(), 2u);
  const ComparisonPointResult& read_dent = result.comparison_points[0];
  const ComparisonPointResult& read_beside = result.comparison_points[1];
  std::printf("  dent %.4g mm (depth %.4g mm, %zu points), beside %.4g mm (%zu points)\n",
              read_dent.deviation * 1e3,
              depth * 1e3,
              read_dent.points,
              read_beside.deviation * 1e3,
              read_beside.points);
  // The cap is flat to 4 % of its depth within 0.2 of its radius; the noise averages down.
  EXPECT_NEAR(read_dent.deviation, depth, 0.1 * std::abs(depth));
  EXPECT_GE(read_dent.points, 10u);
  EXPECT_EQ(read_dent.verdict, Verdict::kPass) << read_dent.verdict_reason;  // the part's ±30 σ
  EXPECT_DOUBLE_EQ(read_dent.tolerance.upper, 30.0 * sigma);
  EXPECT_NEAR(read_beside.deviation, 0.0, 1.0 * sigma);
  EXPECT_EQ(read_beside.verdict, Verdict::kPass) << read_beside.verdict_reason;
  EXPECT_LT(read_dent.off_surface, 1e-9);
  EXPECT_EQ(result.verdict, Verdict::kPass) << result.verdict_reason;

  // The dent's point with a band of its own that the dent leaves: the part fails by it.
  config.comparison_points[0].has_tolerance = true;
  config.comparison_points[0].tolerance = {5.0 * sigma, -5.0 * sigma};
  const InspectionResult failed = inspect(blade(), dented.scan, config);
  ASSERT_EQ(failed.comparison_points.size(), 2u);
  EXPECT_EQ(failed.comparison_points[0].verdict, Verdict::kFail);
  EXPECT_EQ(failed.verdict, Verdict::kFail);
  EXPECT_NE(failed.verdict_reason.find("comparison point 'dent' fails"), std::string::npos)
      << failed.verdict_reason;

  // A point given in millimetres: not on the CAD, the part not evaluated.
  config.comparison_points[0] = at_dent;
  config.comparison_points[1].position = 1000.0 * away;
  const InspectionResult misplaced = inspect(blade(), dented.scan, config);
  ASSERT_EQ(misplaced.comparison_points.size(), 2u);
  EXPECT_EQ(misplaced.comparison_points[1].verdict, Verdict::kNotEvaluated);
  EXPECT_EQ(misplaced.verdict, Verdict::kNotEvaluated);
  EXPECT_NE(misplaced.verdict_reason.find("comparison point 'beside'"), std::string::npos)
      << misplaced.verdict_reason;
  EXPECT_NE(misplaced.verdict_reason.find("off the CAD surface"), std::string::npos);

  // No pose: every point reported by name, not evaluated.
  Scan few;
  for (int i = 0; i < 60; ++i) {
    few.points.emplace_back(0.001 * i, 0.0005 * (i % 7), 0.0003 * (i % 5));
  }
  const InspectionResult unposed = inspect(blade(), few, config);
  EXPECT_NE(unposed.registration, RegistrationStatus::kOk);
  ASSERT_EQ(unposed.comparison_points.size(), 2u);
  EXPECT_EQ(unposed.comparison_points[0].name, "dent");
  for (const ComparisonPointResult& point : unposed.comparison_points) {
    EXPECT_EQ(point.verdict, Verdict::kNotEvaluated);
    EXPECT_FALSE(point.measured());
    EXPECT_NE(point.verdict_reason.find("the part is not"), std::string::npos);
  }
}

// A blade whose airfoil bends above 80 mm of span (the tip 0.6 mm along −y, growing with the
// square of the height), registered from scratch. A six-point nest below the bend fixes the frame
// the unbent blade defines, so a comparison point near the tip reads the bend there; the best fit
// moves the part part of the way into the bend and reads less of it. σ = 0.02 % of L (32 µm).
TEST(Inspection, DatumFrameReadsABentTipWhereTheBestFitSharesIt) {
  const double sigma = 0.0002 * diagonal();
  const double start = 0.08;  // [m] the bend starts here, in the CAD's z (span)
  const double tip = 0.0006;  // [m] its displacement at the top (z = 139 mm)
  const auto bend = [&](const Eigen::Vector3d& on_cad) {
    const double s = std::max(0.0, (on_cad.z() - start) / (0.139 - start));
    return Eigen::Vector3d(0.0, -tip * s * s, 0.0);
  };
  SyntheticScan bent = makeCase(5, 0.0002, false);
  for (Eigen::Vector3d& p : bent.scan.points) {
    const Eigen::Vector3d on_cad = bent.T_cad_scan * p;
    p = bent.T_cad_scan.inverse() * (on_cad + bend(on_cad));
  }
  bent.scan.normals.clear();  // the bend turns them; the cloud's own are estimated
  const auto target = [](const std::string& name, const Eigen::Vector3d& at) {
    ComparisonPointConfig point;
    point.name = name;
    point.datum = name.substr(0, 1);
    point.position = at;
    point.radius = 0.004;
    return point;
  };
  // Vertices of blade_fine.stl (as data/blade/blade_datums.yaml, A3 and B2 at 75 mm).
  std::vector<ComparisonPointConfig> points = {
      target("A1", {-0.001534398, -0.000819943, 0.045052631}),
      target("A2", {0.016648952, -0.000218813, 0.045052631}),
      target("A3", {0.006375238, -0.002104386, 0.075052635}),
      target("B1", {-0.01442154, -0.000176553, 0.045052631}),
      target("B2", {-0.012188326, 0.001875726, 0.075052635}),
      target("C1", {0.000258296, -0.000422718, 0.0})};
  ComparisonPointConfig near_tip = target("near_tip", {0.007617492, -0.005424567, 0.130315796});
  near_tip.datum.clear();
  points.push_back(near_tip);
  const ClosestPoint at_tip = blade().query().closest(near_tip.position);
  const double expected = at_tip.normal.dot(bend(at_tip.point));

  PipelineConfig config = withBand(30.0 * sigma);
  config.comparison_points = points;
  const InspectionResult datums = inspect(blade(), bent.scan, config);
  ASSERT_EQ(datums.registration, RegistrationStatus::kOk) << datums.status.message;
  ASSERT_TRUE(datums.datum_alignment.aligned) << datums.datum_alignment.message;
  for (ComparisonPointConfig& point : config.comparison_points) {
    point.datum.clear();
  }
  const InspectionResult best_fit = inspect(blade(), bent.scan, config);
  ASSERT_EQ(best_fit.registration, RegistrationStatus::kOk) << best_fit.status.message;
  EXPECT_FALSE(best_fit.datum_alignment.requested);
  const double read_datums = datums.comparison_points.back().deviation;
  const double read_best_fit = best_fit.comparison_points.back().deviation;
  const Eigen::Isometry3d truth = bent.T_cad_scan;
  const auto turn = [&](const Eigen::Isometry3d& pose) {
    return Eigen::AngleAxisd(pose.linear().transpose() * truth.linear()).angle() * 180.0 / kPi;
  };
  std::printf(
      "  near the tip: bend %.4g mm, datum frame %.4g mm, best fit %.4g mm; "
      "turn from the truth: datums %.4g deg, best fit %.4g deg\n",
      expected * 1e3,
      read_datums * 1e3,
      read_best_fit * 1e3,
      turn(datums.T_cad_scan),
      turn(best_fit.T_cad_scan));
  // Every target reads zero in the datum frame, within the rounds' stop (targets moving less
  // than a thousandth of their 4 mm radius) and the medians' steps.
  for (const DatumTargetReading& t : datums.datum_alignment.targets) {
    EXPECT_LT(std::abs(t.aligned), 0.1 * sigma) << t.name;
    EXPECT_GE(t.points, 50u) << t.name;
  }
  // The frame is the targets', not the start's: aligned from the truth it is the same.
  const DatumAlignment from_truth = alignToDatums(
      blade().query(), bent.scan.points, truth, points, {}, blade().cellSize(), 0.05 * diagonal());
  ASSERT_TRUE(from_truth.aligned) << from_truth.message;
  const double apart =
      Eigen::AngleAxisd(from_truth.T_cad_scan.linear().transpose() * datums.T_cad_scan.linear())
          .angle() *
      180.0 / kPi;
  EXPECT_LT(apart, 0.02);
  // The readings' noise (σ / √n over ~100 points, levers of 18-75 mm) leaves the frame a few
  // hundredths of a degree from the truth, which the tip, 85 mm beyond the targets, reads
  // amplified; the best fit, moved part of the way into the bend, reads less of it.
  EXPECT_LT(turn(datums.T_cad_scan), 0.1);
  EXPECT_NEAR(read_datums, expected, 0.2 * expected);
  EXPECT_LT(std::abs(read_datums - expected), std::abs(read_best_fit - expected));
}

// Stock left for a later operation on the blade's root (the CAD below z = 20 mm): its faces that
// look up the blade (outward normal along +z) stand 3 σ proud, too little for the trimmed ICP to
// drop as outliers. The whole scan's best fit moves the part to split the difference (1.4 σ at
// the scan's centroid); with the root left out of the alignment (align: false) the pose is the
// airfoil's (0.14 σ: the airfoil alone holds the pose less firmly than the whole blade), and the
// stock reads as it is. At 6 σ and more the trimming already drops the stock from the fit.
TEST(Inspection, RegionsThatDoNotAlignLeaveThePoseToTheRest) {
  const double sigma = 0.001 * diagonal();
  const double stock = 3.0 * sigma;
  SyntheticScan stocked = makeCase(4, 0.001, false);
  const Eigen::Matrix3d R_scan_cad = stocked.T_cad_scan.linear().transpose();
  std::vector<std::size_t> raised;
  for (std::size_t i = 0; i < stocked.scan.points.size(); ++i) {
    const ClosestPoint on = blade().query().closest(stocked.T_cad_scan * stocked.scan.points[i]);
    if (on.point.z() < 0.02 && on.normal.z() > 0.5) {
      stocked.scan.points[i] += stock * (R_scan_cad * on.normal);
      raised.push_back(i);
    }
  }
  RegionConfig root;
  root.name = "root";
  root.boxes.push_back({Eigen::Vector3d(-1.0, -1.0, -1.0), Eigen::Vector3d(1.0, 1.0, 0.02)});
  PipelineConfig config = withBand(5.0 * sigma);
  config.regions = {root};
  const InspectionResult whole = inspect(blade(), stocked.scan, config);
  config.regions[0].align = false;
  const InspectionResult datum = inspect(blade(), stocked.scan, config);
  ASSERT_EQ(whole.registration, RegistrationStatus::kOk) << whole.status.message;
  ASSERT_EQ(datum.registration, RegistrationStatus::kOk) << datum.status.message;
  ASSERT_EQ(datum.deviation_map.size(), stocked.scan.points.size());
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : stocked.scan.points) {
    centroid += p / static_cast<double>(stocked.scan.points.size());
  }
  const auto shift = [&](const InspectionResult& r) {
    return (r.T_cad_scan * centroid - stocked.T_cad_scan * centroid).norm();
  };
  const auto stockRead = [&](const InspectionResult& r) {
    double sum = 0.0;
    for (const std::size_t i : raised) {
      sum += r.deviation_map.deviation[i];
    }
    return sum / static_cast<double>(raised.size());
  };
  std::printf(
      "%zu points raised by 3 sigma; whole scan: %.4f deg, %.3f sigma off, stock reads "
      "%.2f sigma; aligned on the rest: %.4f deg, %.3f sigma off, stock reads %.2f sigma\n",
      raised.size(),
      rotationDeg(whole.T_cad_scan, stocked.T_cad_scan),
      shift(whole) / sigma,
      stockRead(whole) / sigma,
      rotationDeg(datum.T_cad_scan, stocked.T_cad_scan),
      shift(datum) / sigma,
      stockRead(datum) / sigma);
  EXPECT_GT(raised.size(), 1000u);
  EXPECT_GT(shift(whole), 1.0 * sigma);
  EXPECT_LT(shift(datum), 0.3 * sigma);
  EXPECT_NEAR(stockRead(datum), stock, 0.3 * sigma);
  EXPECT_LT(stockRead(whole), stock - 0.5 * sigma);
  EXPECT_NE(datum.status.message.find("regions that align"), std::string::npos)
      << datum.status.message;
  EXPECT_EQ(whole.status.message.find("regions that align"), std::string::npos);
  // From a known pose (here the truth) the same refit, before the offset from it is measured.
  const InspectionResult refined = inspectFrom(blade(), stocked.scan, stocked.T_cad_scan, config);
  ASSERT_EQ(refined.registration, RegistrationStatus::kOk) << refined.status.message;
  EXPECT_NE(refined.status.message.find("regions that align"), std::string::npos);
  EXPECT_LT(shift(refined), 0.3 * sigma);
  EXPECT_NEAR(
      refined.offset_from_initial_deg, rotationDeg(refined.T_cad_scan, stocked.T_cad_scan), 1e-6);
  // Nothing left to align on: the whole scan's pose, said so.
  config.regions[0].boxes[0] = {Eigen::Vector3d::Constant(-1.0), Eigen::Vector3d::Constant(1.0)};
  const InspectionResult nothing = inspect(blade(), stocked.scan, config);
  EXPECT_TRUE(nothing.T_cad_scan.isApprox(whole.T_cad_scan, 0.0));
  EXPECT_NE(::testing::PrintToString(nothing.warnings).find("regions that align"),
            std::string::npos);
}

TEST(Inspection, ScanDescriptorsMustBeComputedLikeTheModels) {
  // The blade was loaded with the default descriptor settings; a pipeline with other ones would
  // compare descriptors computed two ways. It is refused before any stage runs, with a status
  // that says why, and no pose.
  const SyntheticScan scan = makeCase(3, 0.002, false);
  PipelineConfig other;
  other.descriptor.coarse_ball_cells = 2.4;
  std::vector<std::string> stages;
  const InspectionResult refused =
      inspect(blade(), scan.scan, other, [&](const std::string& stage, double) {
        stages.push_back(stage);
        return true;
      });
  EXPECT_EQ(refused.status.code, StatusCode::kInvalidInput);
  EXPECT_NE(refused.status.message.find("descriptor settings"), std::string::npos);
  EXPECT_EQ(refused.registration, RegistrationStatus::kFailed);
  EXPECT_EQ(refused.verdict, Verdict::kNotEvaluated);
  EXPECT_TRUE(stages.empty());
  // The same settings in a model loaded with them: registered.
  const ModelLoadResult matching = loadModel(kBlade, 0.001, "blade", other.descriptor);
  ASSERT_TRUE(matching.status.ok()) << matching.status.message;
  EXPECT_NE(matching.model->descriptorKey(), blade().descriptorKey());
  const InspectionResult registered = inspect(*matching.model, scan.scan, other);
  EXPECT_EQ(registered.registration, RegistrationStatus::kOk) << registered.status.message;
}

// ISO 14253-1's decision rule with a measurement uncertainty U = 5 σ on a band of ±20 σ: PASS
// only inside ±15 σ (conformance proven), FAIL only beyond ±25 σ (nonconformance proven). A
// dent 22 σ deep fails on the band alone but proves nothing with U; one 32 σ deep fails either
// way; a clean part passes either way. U of half the band or more proves no part conforms.
TEST(Inspection, GuardBandsOfTheMeasurementUncertaintyDecideOnlyWhatTheyProve) {
  const double sigma = 0.0005 * diagonal();
  PipelineConfig simple = withBand(20.0 * sigma);
  PipelineConfig guarded = simple;
  guarded.verdict.measurement_uncertainty = 5.0 * sigma;
  const SyntheticScan clean = makeCase(3, 0.0005, false);
  struct Case {
    const char* name;
    double depth;  // [σ], 0: clean
    Verdict simple;
    Verdict guarded;
  };
  for (const Case& c : {Case{"clean", 0.0, Verdict::kPass, Verdict::kPass},
                        Case{"dent of 22 sigma", -22.0, Verdict::kFail, Verdict::kNotEvaluated},
                        Case{"dent of 32 sigma", -32.0, Verdict::kFail, Verdict::kFail}}) {
    SCOPED_TRACE(c.name);
    SyntheticScan scan = clean;
    if (c.depth < 0.0) {
      pressDent(&scan, 0.05, c.depth * sigma);
    }
    const InspectionResult plain = inspect(blade(), scan.scan, simple);
    const InspectionResult result = inspect(blade(), scan.scan, guarded);
    ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
    const ConformanceZones& zones = result.conformance;
    std::printf(
        "  %s: %s without U, %s with U (%zu regions outside the acceptance zone, %zu "
        "beyond the rejection limits): %s\n",
        c.name,
        toString(plain.verdict),
        toString(result.verdict),
        zones.regions_outside_acceptance,
        zones.regions_beyond_rejection,
        result.verdict_reason.c_str());
    EXPECT_EQ(plain.verdict, c.simple) << plain.verdict_reason;
    EXPECT_EQ(plain.conformance.measurement_uncertainty, 0.0);
    EXPECT_EQ(result.verdict, c.guarded) << result.verdict_reason;
    EXPECT_NEAR(zones.acceptance_upper, 15.0 * sigma, 1e-12);
    EXPECT_NEAR(zones.rejection_lower, -25.0 * sigma, 1e-12);
    EXPECT_NE(result.verdict_reason.find("ISO 14253-1"), std::string::npos);
    // The defect list is the band's, whatever U.
    EXPECT_EQ(result.defects.size(), plain.defects.size());
  }

  guarded.verdict.measurement_uncertainty = 20.0 * sigma;
  const InspectionResult unprovable = inspect(blade(), clean.scan, guarded);
  EXPECT_EQ(unprovable.verdict, Verdict::kNotEvaluated);
  EXPECT_NE(unprovable.verdict_reason.find("half the tolerance band"), std::string::npos)
      << unprovable.verdict_reason;

  guarded.verdict.measurement_uncertainty = -sigma;
  EXPECT_FALSE(validate(guarded).empty());
}

TEST(Inspection, ABandNarrowerThanTheNoiseIsFlagged) {
  const SyntheticScan truth = makeCase(7, 0.005, false);
  const InspectionResult result = inspect(blade(), truth.scan, withBand(0.001 * diagonal()));
  ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  EXPECT_EQ(result.verdict, Verdict::kFail);
  bool flagged = false;
  for (const auto& warning : result.warnings) {
    flagged =
        flagged || warning.find("narrower than 3x the fit's residual noise") != std::string::npos;
  }
  EXPECT_TRUE(flagged);
}

// The inspection's detection limits at a metrology scanner's noise (docs/accuracy.md), from an
// unknown pose: a dent inside the band is no defect, one half as deep again as the band is
// found where it lies, its peak read one to two σ deeper than it is (the deepest of its noisy
// points); a drawing allowing flaws of that area passes it (defects.min_area); and the
// registration adds to each deviation a small fraction of the noise.
TEST(Inspection, DentsBeyondTheBandAreFoundAndTheRegistrationAddsLittleToTheDeviation) {
  const double sigma = 0.0002 * diagonal();
  const double band = 4.0 * sigma;
  const PipelineConfig config = withBand(band);
  for (std::uint64_t seed = 11; seed <= 12; ++seed) {
    const SyntheticScan clean = makeCase(seed, 0.0002, false);
    const InspectionResult reference = inspect(blade(), clean.scan, config);
    ASSERT_EQ(reference.registration, RegistrationStatus::kOk) << reference.status.message;
    EXPECT_EQ(reference.verdict, Verdict::kPass) << reference.verdict_reason;

    // Every deviation at the registered pose against the same point's at the true pose.
    const DeviationMap& map = reference.deviation_map;
    const Eigen::Isometry3d T_true_registered = clean.T_cad_scan * reference.T_cad_scan.inverse();
    Points at_truth;
    for (const auto& p : map.points) {
      at_truth.push_back(T_true_registered * p);
    }
    Points normals;  // the scanner's, which the pipeline measures along
    for (const auto& n : clean.scan.normals) {
      normals.push_back(clean.T_cad_scan.linear() * n);
    }
    const SurfaceDistances exact = measureDeviation(
        blade(), at_truth, 0.05 * diagonal(), normals, config.deviation.facing_tolerance_deg);
    double sum_sq = 0.0, largest = 0.0;
    std::size_t compared = 0;
    for (std::size_t i = 0; i < map.size(); ++i) {
      const double added = static_cast<double>(map.deviation[i]) - exact.deviation[i];
      if (std::isfinite(added)) {
        sum_sq += added * added;
        largest = std::max(largest, std::abs(added));
        ++compared;
      }
    }
    const double added_rms =
        std::sqrt(sum_sq / static_cast<double>(std::max<std::size_t>(1, compared)));
    std::printf("  the registration adds RMS %.3g sigma, at most %.3g sigma (%zu points)\n",
                added_rms / sigma,
                largest / sigma,
                compared);
    EXPECT_GT(compared, clean.scan.points.size() * 99 / 100);
    EXPECT_LT(added_rms, 0.1 * sigma);
    EXPECT_LT(largest, 0.5 * sigma);

    for (const double depth_in_bands : {0.8, 1.5}) {
      SyntheticScan dented = clean;
      const SurfaceDefect dent = pressDent(&dented, 0.03, -depth_in_bands * band);
      const InspectionResult result = inspect(blade(), dented.scan, config);
      ASSERT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
      std::printf("  dent r %.3g mm, %.2f bands deep: %s, %zu regions",
                  dent.radius * 1e3,
                  depth_in_bands,
                  toString(result.verdict),
                  result.defects.size());
      if (depth_in_bands < 1.0) {
        std::printf("\n");
        EXPECT_EQ(result.verdict, Verdict::kPass) << result.verdict_reason;
        EXPECT_TRUE(result.defects.empty());
        continue;
      }
      ASSERT_EQ(result.defects.size(), 1u);
      const DefectRegion& found = result.defects.front();
      std::printf("; peak %.3g sigma from the depth, %.3g mm from the centre\n",
                  (found.peak - dent.depth) / sigma,
                  (found.centroid - dent.centre).norm() * 1e3);
      EXPECT_EQ(result.verdict, Verdict::kFail);
      EXPECT_EQ(found.sign, -1);
      EXPECT_LT((found.centroid - dent.centre).norm(), 0.5 * dent.radius);
      EXPECT_LT(found.peak, dent.depth + sigma);
      EXPECT_GT(found.peak, dent.depth - 4.0 * sigma);

      // A drawing that allows flaws of twice its area passes it, and says by what rule.
      PipelineConfig allowing = config;
      allowing.defects.min_area = 2.0 * found.area;
      const InspectionResult allowed = inspectAt(blade(), dented.scan, result.T_cad_scan, allowing);
      EXPECT_EQ(allowed.verdict, Verdict::kPass) << allowed.verdict_reason;
      EXPECT_NE(allowed.verdict_reason.find("mm^2 or more"), std::string::npos)
          << allowed.verdict_reason;
    }
  }
}

// A 1 mm plate scanned from above with the scanner's normals, a dent 0.8 mm deep pressed into
// its top: deeper than half the wall, so its points lie nearer the bottom face. Measured along
// their normals they read the dent's depth, not the 0.2 mm left to the far side
// (deviation.facing_tolerance_deg); with 180 degrees they read the far side.
TEST(Inspection, AThinWallDentedPastItsMiddleReadsItsDepthAlongTheScannersNormals) {
  const Model plate(test::makeBox(Eigen::Vector3d(0.02, 0.015, 0.0005)), "plate", "test");
  const SurfaceDefect dent{Eigen::Vector3d(0.0, 0.0, 0.0005), 0.004, -0.0008};
  Scan scan;
  for (int i = -38; i <= 38; ++i) {
    for (int j = -28; j <= 28; ++j) {
      const Eigen::Vector3d top(0.0005 * i, 0.0005 * j, 0.0005);
      scan.points.push_back(top + defectDisplacement(dent, top) * Eigen::Vector3d::UnitZ());
      scan.normals.push_back(Eigen::Vector3d::UnitZ());
    }
  }
  PipelineConfig config = withBand(0.0001);
  const InspectionResult result = inspectAt(plate, scan, Eigen::Isometry3d::Identity(), config);
  ASSERT_EQ(result.defects.size(), 1u) << result.verdict_reason;
  std::printf("  along the normals: peak %.4g mm over %.3g mm^2\n",
              result.defects[0].peak * 1e3,
              result.defects[0].area * 1e6);
  EXPECT_EQ(result.verdict, Verdict::kFail);
  EXPECT_NEAR(result.defects[0].peak, -0.0008, 1e-7);
  EXPECT_LT(result.deviation.min, -0.0008 + 1e-7);

  config.deviation.facing_tolerance_deg = 180.0;
  const InspectionResult nearest = inspectAt(plate, scan, Eigen::Isometry3d::Identity(), config);
  ASSERT_FALSE(nearest.defects.empty());
  std::printf("  to the nearest face: peak %.4g mm\n", nearest.defects[0].peak * 1e3);
  // No reading can be deeper than half the wall: the dent is read at its mid-wall points.
  EXPECT_NEAR(nearest.defects[0].peak, -0.0005, 1e-5);
}

TEST(Inspection, ProgressReportsEveryStageAndCancelStopsBeforeOne) {
  const SyntheticScan truth = makeCase(8, 0.002, false);
  std::vector<std::string> stages;
  std::vector<double> fractions;
  const auto record = [&](const std::string& stage, double fraction) {
    stages.push_back(stage);
    fractions.push_back(fraction);
    return true;
  };
  const InspectionResult full = inspect(blade(), truth.scan, PipelineConfig(), record);
  ASSERT_EQ(full.registration, RegistrationStatus::kOk) << full.status.message;
  const std::vector<std::string> all = {"clean",
                                        "supports",
                                        "descriptors",
                                        "features",
                                        "correspondences",
                                        "global_registration",
                                        "icp",
                                        "verification",
                                        "deviation"};
  EXPECT_EQ(stages, all);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_GE(fractions.front(), 0.0);
  EXPECT_LE(fractions.back(), 1.0);

  stages.clear();
  const auto cancel_at_icp = [&](const std::string& stage, double) {
    stages.push_back(stage);
    return stage != "icp";
  };
  const InspectionResult cancelled = inspect(blade(), truth.scan, PipelineConfig(), cancel_at_icp);
  EXPECT_EQ(stages, std::vector<std::string>(all.begin(), all.end() - 2));  // up to icp
  EXPECT_EQ(cancelled.status.code, StatusCode::kCancelled);
  EXPECT_EQ(cancelled.verdict, Verdict::kNotEvaluated);
  EXPECT_NE(cancelled.verdict_reason.find("cancelled before stage icp"), std::string::npos)
      << cancelled.verdict_reason;
  EXPECT_TRUE(cancelled.deviation_map.points.empty());
  EXPECT_EQ(cancelled.timings.back().stage, "total");
}

}  // namespace
}  // namespace freeform_inspection
