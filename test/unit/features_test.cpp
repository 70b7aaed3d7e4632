// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// Feature selection (eq. 12–13) and candidate search on descriptor tables whose answer is known.
#include "freeform_inspection/features.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "freeform_inspection/correspondence.h"

namespace freeform_inspection {
namespace {

constexpr unsigned kSeed = 5;

// n values from N(0.4, 0.01²) with `outliers` extreme ones (0.1) at the end.
Eigen::VectorXd columnWithOutliers(int n, int outliers, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.4, 0.01);
  Eigen::VectorXd values(n);
  for (int i = 0; i < n; ++i) {
    values[i] = i >= n - outliers ? 0.1 : noise(rng);
  }
  return values;
}

TEST(RareAtScale, ExtremeValuesAreRareAndTheBulkIsNot) {
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  const Eigen::VectorXd values = columnWithOutliers(5000, 20, kSeed);
  const std::vector<bool> rare = rareAtScale(values, 0.02);
  int rare_count = 0;
  for (int i = 0; i < 5000; ++i) {
    rare_count += rare[static_cast<std::size_t>(i)] ? 1 : 0;
  }
  for (int i = 4980; i < 5000; ++i) {
    EXPECT_TRUE(rare[static_cast<std::size_t>(i)]) << i;
  }
  // The rare bins hold fewer than s = 2 % of the points (paper §3.4 step 2).
  EXPECT_LT(rare_count, 100);
  EXPECT_GE(rare_count, 20);
}

TEST(RareAtScale, ScottBinWidthFollowsEquation12) {
  // 504 values at 0, 495 at 1, one at 0.5: σ ≈ 0.5, so h = 3.49·σ·n^(−1/3) ≈ 0.17 (eq. 12–13)
  // and 0.5 sits alone in its bin, far from both clusters: it is the only rare value. (With a
  // bin as wide as the range, nothing would be.)
  Eigen::VectorXd values = Eigen::VectorXd::Zero(1000);
  values.tail(495).setConstant(1.0);
  values[0] = 0.5;  // alone in the middle bin
  const std::vector<bool> rare = rareAtScale(values, 0.02);
  EXPECT_TRUE(rare[0]);
  EXPECT_FALSE(rare[1]);
  EXPECT_FALSE(rare[999]);
}

TEST(RareAtScale, ConstantValuesHaveNothingRare) {
  const std::vector<bool> rare = rareAtScale(Eigen::VectorXd::Constant(100, 0.5), 0.02);
  for (const bool r : rare) {
    EXPECT_FALSE(r);
  }
}

// Cells on a line 1 cm apart; descriptor columns with rare values at chosen cells and scales.
struct Table {
  Points positions;
  Eigen::MatrixXd values;
};

Table lineTable(int n, int scales) {
  Table table;
  for (int i = 0; i < n; ++i) {
    table.positions.emplace_back(0.01 * i, 0.0, 0.0);
  }
  table.values.resize(n, scales);
  for (int k = 0; k < scales; ++k) {
    table.values.col(k) = columnWithOutliers(n, 0, kSeed + static_cast<unsigned>(k));
  }
  return table;
}

TEST(SelectFeatures, NeedsPersistenceOverAThirdOfTheScales) {
  Table table = lineTable(2000, 6);
  // Cell 100: rare at scales 1–2 (persistent, K/3 = 2). Cell 900: rare at scale 1 and 3 only
  // (not consecutive). Cell 1500: rare at scales 4–6.
  table.values(100, 0) = table.values(100, 1) = 0.1;
  table.values(900, 0) = table.values(900, 2) = 0.1;
  table.values(1500, 3) = table.values(1500, 4) = table.values(1500, 5) = 0.9;
  FeatureConfig config;
  config.min_features = 3;
  const FeatureResult result = selectFeatures(table.positions, table.values, 0.1, config);
  const auto has = [&](int cell) {
    return std::find(result.cells.begin(), result.cells.end(), cell) != result.cells.end();
  };
  EXPECT_TRUE(has(100));
  EXPECT_TRUE(has(1500));
  EXPECT_FALSE(has(900));
  // Cell 1500 is rare on three scales, so it ranks above cell 100.
  ASSERT_GE(result.cells.size(), 2U);
  EXPECT_EQ(result.cells[0], 1500);
  EXPECT_EQ(result.rare_scales[0] & 0b111000U, 0b111000U);
}

TEST(SelectFeatures, KeepsOneFeaturePerRegion) {
  Table table = lineTable(2000, 6);
  for (int cell = 500; cell < 510; ++cell) {  // a 10 cm rare region
    table.values.row(cell).setConstant(0.1);
  }
  FeatureConfig config;
  config.separation_ratio = 0.5;  // R_s = 5 cm with r_max = 10 cm
  const FeatureResult result = selectFeatures(table.positions, table.values, 0.1, config);
  int in_region = 0;
  for (std::size_t i = 0; i < result.cells.size(); ++i) {
    in_region += result.cells[i] >= 500 && result.cells[i] < 510 ? 1 : 0;
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_GE((table.positions[static_cast<std::size_t>(result.cells[i])] -
                 table.positions[static_cast<std::size_t>(result.cells[j])])
                    .norm(),
                0.05 - 1e-12);
    }
  }
  EXPECT_EQ(in_region, 2);  // the region is 9 cm long: two representatives 5 cm apart fit
}

TEST(SelectFeatures, FeaturelessSurfaceFailsWithAMessage) {
  const Points positions(50, Eigen::Vector3d::Zero());
  const FeatureResult result =
      selectFeatures(positions, Eigen::MatrixXd::Constant(50, 6, 0.5), 0.1, FeatureConfig());
  EXPECT_EQ(result.status.code, StatusCode::kRegistrationFailed);
  EXPECT_NE(result.status.message.find("rare features"), std::string::npos);
}

TEST(SelectFeatures, MismatchedInputIsRefused) {
  const FeatureResult result =
      selectFeatures(Points(3), Eigen::MatrixXd::Zero(4, 6), 0.1, FeatureConfig());
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
}

TEST(FeatureConfig, ValidationNamesTheField) {
  FeatureConfig config;
  config.rare_fraction = 0.0;
  config.max_features = 2;
  const auto errors = validate(config);
  ASSERT_EQ(errors.size(), 3U);  // rare_fraction, max_features, min_features > max_features
  EXPECT_NE(errors[0].find("features.rare_fraction"), std::string::npos);
}

TEST(FindCandidates, BestAgreementFirstWithinTheTolerance) {
  // CAD cells 0..99 on a line; descriptor of cell c is 0.3 + 0.002·c at every scale.
  Points cad_positions;
  Eigen::MatrixXd cad(100, 6);
  for (int c = 0; c < 100; ++c) {
    cad_positions.emplace_back(0.01 * c, 0.0, 0.0);
    cad.row(c).setConstant(0.3 + 0.002 * c);
  }
  Eigen::MatrixXd scan = Eigen::MatrixXd::Constant(1, 6, 0.3 + 0.002 * 40 + 0.0005);
  CorrespondenceConfig config;
  config.descriptor_tolerance = 0.0046;  // cells 38..42 agree within it
  config.min_candidates = 1;
  config.separation_cells = 0.0;
  const CorrespondenceResult result = findCandidates(scan, {0}, cad, cad_positions, 0.01, config);
  ASSERT_TRUE(result.status.ok());
  ASSERT_EQ(result.features.size(), 1U);
  const std::vector<int> expected = {40, 41, 39, 42, 38};
  EXPECT_EQ(result.features[0].cad, expected);
  EXPECT_NEAR(result.features[0].descriptor_distance[0], 0.0005, 1e-12);
  EXPECT_EQ(result.candidates, 5U);
}

TEST(FindCandidates, SpreadsCandidatesAndKeepsAMinimum) {
  Points cad_positions;
  Eigen::MatrixXd cad(100, 6);
  for (int c = 0; c < 100; ++c) {
    cad_positions.emplace_back(0.01 * c, 0.0, 0.0);
    cad.row(c).setConstant(0.3 + 0.002 * c);
  }
  const Eigen::MatrixXd scan = Eigen::MatrixXd::Constant(1, 6, 0.9);  // matches nothing
  CorrespondenceConfig config;
  config.min_candidates = 3;
  config.separation_cells = 2.5;  // 2.5 cm apart
  const CorrespondenceResult result = findCandidates(scan, {0}, cad, cad_positions, 0.01, config);
  const std::vector<int> expected = {99, 96, 93};  // nearest values, at least 3 cells apart
  EXPECT_EQ(result.features[0].cad, expected);
}

}  // namespace
}  // namespace freeform_inspection
