// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/pipeline.h"

#include <stdexcept>

#include "test_shapes.h"
#include <gtest/gtest.h>

namespace freeform_inspection {
namespace {

const Eigen::Vector3d kHalf(0.05, 0.03, 0.02);

Model boxModel() {
  return Model(test::makeBox(kHalf), "box", "test");
}

TEST(Inspect, ValidScanReportsNotImplementedNeverAnIdentityPoseAsAnAnswer) {
  Scan scan;
  scan.points = test::sampleBoxSurface(kHalf, 400, 3);
  const InspectionResult result = inspect(boxModel(), scan, PipelineConfig());
  EXPECT_EQ(result.status.code, StatusCode::kNotImplemented);
  EXPECT_EQ(result.registration, RegistrationStatus::kFailed);
  EXPECT_EQ(result.verdict, Verdict::kNotEvaluated);
  EXPECT_EQ(result.counts.scan_points, 400u);
  EXPECT_EQ(result.counts.cad_vertices, 8u);
  ASSERT_FALSE(result.timings.empty());
  EXPECT_EQ(result.timings.front().stage, "clean");
  EXPECT_EQ(result.timings.back().stage, "total");
  EXPECT_GE(result.timings.back().seconds, result.timings.front().seconds);
}

TEST(Inspect, StopsAtTheCleaningStageWithItsStatus) {
  Scan scan;
  scan.points = {{0, 0, 0}};
  const InspectionResult result = inspect(boxModel(), scan, PipelineConfig());
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput);
  EXPECT_EQ(result.verdict, Verdict::kNotEvaluated);
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
  const auto errors = validate(config);
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_NE(errors[0].find("input.min_points"), std::string::npos);
  EXPECT_NE(errors[1].find("input.max_extent_ratio"), std::string::npos);
  EXPECT_NE(errors[2].find("tolerance.lower"), std::string::npos);
}

TEST(StatusNames, AreStableForJsonAndMessages) {
  EXPECT_STREQ(toString(StatusCode::kUnitsMismatch), "units_mismatch");
  EXPECT_STREQ(toString(RegistrationStatus::kAmbiguous), "ambiguous");
  EXPECT_STREQ(toString(Verdict::kNotEvaluated), "NOT_EVALUATED");
}

}  // namespace
}  // namespace freeform_inspection
