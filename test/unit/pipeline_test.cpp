// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/pipeline.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "analytic_clouds.h"
#include "analytic_shapes.h"
#include "test_shapes.h"
#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace freeform_inspection {
namespace {

const Eigen::Vector3d kHalf(0.05, 0.03, 0.02);

Model boxModel() {
  return Model(test::makeBox(kHalf), "box", "test");
}

// The one rigidity check of a caller's pose (inspectFrom's initial pose, the virtual sensor's):
// a turn and a shift pass; a scale, a mirror, a shear, a NaN or an infinite shift do not.
TEST(RigidTransform, TellsATurnAndShiftFromWhatIsNone) {
  Eigen::Matrix4d turned = Eigen::Matrix4d::Identity();
  turned.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(2.0, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  turned.topRightCorner<3, 1>() = Eigen::Vector3d(0.3, -4.0, 12.0);
  EXPECT_TRUE(isRigidTransform(turned, 1e-6));
  EXPECT_TRUE(isRigidTransform(Eigen::Matrix4d::Identity(), 1e-6));
  Eigen::Matrix4d scaled = turned;
  scaled.topLeftCorner<3, 3>() *= 1.001;
  EXPECT_FALSE(isRigidTransform(scaled, 1e-6));
  EXPECT_TRUE(isRigidTransform(scaled, 1e-2)) << "within a looser tolerance";
  Eigen::Matrix4d mirrored = turned;
  mirrored.col(0) *= -1.0;
  EXPECT_FALSE(isRigidTransform(mirrored, 1e-6)) << "determinant -1";
  Eigen::Matrix4d sheared = turned;
  sheared(0, 1) += 0.01;
  EXPECT_FALSE(isRigidTransform(sheared, 1e-6));
  Eigen::Matrix4d not_finite = turned;
  not_finite(1, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(isRigidTransform(not_finite, 1e-6));
  not_finite(1, 3) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(isRigidTransform(not_finite, 1e-6));
}

TEST(Inspect, FeaturelessScanFailsWithAReasonNeverAnIdentityPose) {
  // 400 points on a box whose CAD has 8 vertices, seen at the identity: too sparse for rare
  // features to be congruent. The result must say why, not return the identity as an answer.
  Scan scan;
  scan.points = test::sampleBoxSurface(kHalf, 400, 3);
  const InspectionResult result = inspect(boxModel(), scan, PipelineConfig());
  if (result.registration == RegistrationStatus::kFailed) {
    EXPECT_EQ(result.status.code, StatusCode::kRegistrationFailed);
    EXPECT_FALSE(result.status.message.empty());
  } else {
    EXPECT_TRUE(result.registration == RegistrationStatus::kAmbiguous) << result.status.message;
  }
  EXPECT_EQ(result.verdict, Verdict::kNotEvaluated);
  EXPECT_EQ(result.counts.scan_points, 400u);
  EXPECT_EQ(result.counts.cad_vertices, 8u);
  EXPECT_EQ(result.counts.scan_faces, 0u);
  ASSERT_GE(result.timings.size(), 4u);
  EXPECT_EQ(result.timings[0].stage, "clean");
  EXPECT_EQ(result.timings[1].stage, "supports");
  EXPECT_EQ(result.timings[2].stage, "descriptors");
  EXPECT_EQ(result.timings.back().stage, "total");
  EXPECT_GE(result.timings.back().seconds, result.timings.front().seconds);
}

TEST(Inspect, OrganizedRangeImageWithHolesRunsThroughTheDescriptors) {
  // A 50 mm sphere seen by a 96 × 96 pinhole camera from 0.3 m: NaN around the silhouette.
  const Model sphere(test::icosphere(0.05, 4), "sphere", "test");
  const analytic::Pinhole camera{96, 96, 300.0};
  const analytic::OrganizedCloud image =
      analytic::organizedSphere(camera, Eigen::Vector3d(0, 0, 0.3), 0.05);
  Scan scan;
  scan.points = image.points;
  scan.width = image.width;
  scan.height = image.height;
  ASSERT_TRUE(scan.isOrganized());
  std::size_t holes = 0;
  for (const auto& p : scan.points) {
    holes += p.allFinite() ? 0 : 1;
  }
  ASSERT_GT(holes, 0u);
  const InspectionResult result = inspect(sphere, scan, PipelineConfig());
  // A sphere has no rare features: its pose cannot be fixed, and the pipeline says so.
  EXPECT_NE(result.registration, RegistrationStatus::kOk) << result.status.message;
  EXPECT_EQ(result.counts.non_finite, holes);
  EXPECT_EQ(result.counts.scan_points, scan.points.size() - holes);
  // Two triangles per fully finite grid cell: far more faces than points means the grid was used.
  EXPECT_GT(result.counts.scan_faces, 3 * result.counts.scan_points / 2);
  EXPECT_EQ(result.timings[2].stage, "descriptors");
}

TEST(Inspect, StopsAtTheCleaningStageWithItsStatus) {
  Scan scan;
  scan.points = {{0, 0, 0}};
  const InspectionResult result = inspect(boxModel(), scan, PipelineConfig());
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput);
  EXPECT_EQ(result.verdict, Verdict::kNotEvaluated);
}

TEST(Inspect, TableWithNothingOnItIsRefusedNamingTheSupport) {
  // A 0.5 m table, wider than the 123 mm box, and two stray points above it: the table goes as a
  // support and what is left cannot fix a pose; the message says both.
  Scan scan;
  scan.points = analytic::samplePlane(0.5, 5000, 4).points;
  scan.points.emplace_back(0.01, 0.02, 0.05);
  scan.points.emplace_back(-0.03, 0.01, 0.08);
  const InspectionResult result = inspect(boxModel(), scan, PipelineConfig());
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput);
  EXPECT_NE(result.status.message.find("after removing the support (5000 points)"),
            std::string::npos)
      << result.status.message;
  EXPECT_NE(result.status.message.find("2 finite points"), std::string::npos)
      << result.status.message;
  EXPECT_EQ(result.counts.support_points, 5000u);
  EXPECT_EQ(result.registration, RegistrationStatus::kFailed);
  EXPECT_EQ(result.verdict, Verdict::kNotEvaluated);
  ASSERT_FALSE(result.warnings.empty());
  EXPECT_NE(result.warnings.front().find("support plane"), std::string::npos);
}

TEST(Inspect, CroppedScanRefusedForItsSizeCountsTheCropNotNonFinitePoints) {
  // Refused before the cleaning counted anything: the cropped point is not reported as a NaN
  // the scanner sent (the count once wrapped below zero).
  Scan scan;
  scan.points = test::sampleBoxSurface(kHalf, 500, 3);
  scan.points.emplace_back(1.0, 1.0, 1.0);
  PipelineConfig config;
  config.input.max_points = 100;
  config.input.crop_box = {-0.1, -0.1, -0.1, 0.1, 0.1, 0.1};
  const InspectionResult result = inspect(boxModel(), scan, config);
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_NE(result.status.message.find("input.max_points"), std::string::npos);
  EXPECT_EQ(result.counts.cropped, 1u);
  EXPECT_EQ(result.counts.non_finite, 0u);
}

TEST(Inspect, InvalidConfigurationIsACallerErrorAndThrows) {
  PipelineConfig config;
  config.tolerance.upper = -1.0;
  Scan scan;
  scan.points = test::sampleBoxSurface(kHalf, 10, 3);
  EXPECT_THROW(inspect(boxModel(), scan, config), std::invalid_argument);
}

TEST(Validate, NamesEveryBadField) {
  PipelineConfig config;
  EXPECT_TRUE(validate(config).empty());
  config.input.min_points = 2;
  config.input.max_extent_ratio = 0.5;
  config.tolerance.lower = 0.001;
  config.correspondence.retry_candidates = -1;
  const auto errors = validate(config);
  ASSERT_EQ(errors.size(), 4u);
  const auto named = [&](const std::string& field) {
    return std::any_of(errors.begin(), errors.end(), [&](const std::string& e) {
      return e.find(field) != std::string::npos;
    });
  };
  EXPECT_TRUE(named("input.min_points"));
  EXPECT_TRUE(named("input.max_extent_ratio"));
  EXPECT_TRUE(named("tolerance.lower"));
  EXPECT_TRUE(named("correspondence.retry_candidates"));
}

TEST(StatusNames, AreStableForJsonAndMessages) {
  EXPECT_STREQ(toString(StatusCode::kUnitsMismatch), "units_mismatch");
  EXPECT_STREQ(toString(RegistrationStatus::kAmbiguous), "ambiguous");
  EXPECT_STREQ(toString(Verdict::kNotEvaluated), "NOT_EVALUATED");
}

}  // namespace
}  // namespace freeform_inspection

namespace freeform_inspection {
namespace {

// Issue 4's bad inputs, through the whole pipeline: each gets a status naming the problem and
// the registration is "failed" — never a pose reported as ok.
TEST(Inspect, BadScansGetAReasonAndNoPose) {
  const Model box = boxModel();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    std::string name;
    Points points;
    StatusCode code;
    std::string words;
  };
  Points collinear;
  Points planar;
  Points huge;
  for (int i = 0; i < 200; ++i) {
    collinear.emplace_back(0.0005 * i, 0.0, 0.0);
    planar.emplace_back(0.001 * (i % 20), 0.001 * (i / 20), 0.0);
  }
  for (const auto& p : test::sampleBoxSurface(kHalf, 400, 3)) {
    huge.push_back(1000.0 * p);  // the scan in mm, the CAD in m
  }
  const std::vector<Case> cases = {
      {"empty", {}, StatusCode::kInvalidInput, "no finite points"},
      {"all NaN", {{nan, nan, nan}, {nan, 0, 0}}, StatusCode::kInvalidInput, "no finite points"},
      {"two points", {{0, 0, 0}, {0.01, 0, 0}}, StatusCode::kDegenerateInput, "points"},
      {"collinear", collinear, StatusCode::kDegenerateInput, "collinear"},
      {"planar", planar, StatusCode::kDegenerateInput, "planar"},
      {"1000 times larger", huge, StatusCode::kUnitsMismatch, "units"},
  };
  for (const Case& c : cases) {
    Scan scan;
    scan.points = c.points;
    const InspectionResult result = inspect(box, scan, PipelineConfig());
    EXPECT_EQ(result.status.code, c.code) << c.name << ": " << result.status.message;
    EXPECT_NE(result.status.message.find(c.words), std::string::npos)
        << c.name << ": " << result.status.message;
    EXPECT_EQ(result.registration, RegistrationStatus::kFailed) << c.name;
    EXPECT_EQ(result.verdict, Verdict::kNotEvaluated) << c.name;
  }
}

TEST(Inspect, TooFewPointsForTheCurvatureFitIsRefusedWithAReason) {
  // Twenty points pass the input checks but cannot carry a 24-neighbour curvature fit, let alone
  // a triplet of rare features: refused, naming the count.
  Scan scan;
  scan.points = test::sampleBoxSurface(kHalf, 20, 5);
  const InspectionResult result = inspect(boxModel(), scan, PipelineConfig());
  EXPECT_EQ(result.registration, RegistrationStatus::kFailed);
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput) << result.status.message;
  EXPECT_NE(result.status.message.find("20 points"), std::string::npos) << result.status.message;
}

}  // namespace
}  // namespace freeform_inspection
