// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "freeform_inspection/types.h"

/// @file features.h
/// Rare-feature selection on the scan (paper §2.4, §3.4): per scale, a histogram of V_k with
/// Scott's bin width h = 3.49 σ n^(−1/3) (eq. 12–13); the least-populated bins holding fewer than
/// s = 2 % of the points are rare; a point is a feature when it is rare on at least K/3
/// consecutive scales; one representative per region, at least R_s apart.

namespace freeform_inspection {

/// Feature-selection settings.
struct FeatureConfig {
  double rare_fraction = 0.02;    ///< s / n: the rare bins together hold fewer points (paper 2 %)
  int min_persistent_scales = 0;  ///< consecutive rare scales a feature needs; 0 = ⌈K/3⌉ (paper)
  double separation_ratio = 0.5;  ///< R_s / r_max: least distance between two features
  int max_features = 32;          ///< the rarest ones are kept when there are more
  /// A feature's geodesic ball of radius r_max must cover at least this × π r_max² of surface:
  /// near the edge of a partial scan the ball is cut and the descriptor is not the CAD's.
  double min_ball_area = 0.7;
  int min_features = 12;  ///< fewer than this: s is doubled (up to 8×) until there are enough
};

/// @brief One message per invalid field; empty when valid.
std::vector<std::string> validate(const FeatureConfig& config);

/// Selected features: indices into the descriptor rows (surface-graph cells).
struct FeatureResult {
  Status status;
  std::vector<int> cells;                  ///< feature cells, rarest first
  std::vector<std::uint32_t> rare_scales;  ///< per feature: bit k set when rare at scale k
  std::vector<double> rarity;              ///< per feature: Σ over its rare scales of |z-score|
  double rare_fraction_used = 0.0;         ///< s / n after any relaxation
};

/// @brief Selects rare features.
/// @param positions cell centres [m] (for the separation R_s)
/// @param values cells × K descriptor values V_k
/// @param r_max largest kernel radius [m]
/// @param eligible optional: false for cells that must not be features (asked only for rare
/// cells, rarest first, so it may be costly)
FeatureResult selectFeatures(const Points& positions,
                             const Eigen::MatrixXd& values,
                             double r_max,
                             const FeatureConfig& config,
                             const std::function<bool(int)>& eligible = {});

/// @brief Scale k's rare rows: the least-populated Scott's-rule bins whose total count stays
/// below `rare_fraction` × n (ties broken towards the tails, so the result is deterministic).
std::vector<bool> rareAtScale(const Eigen::VectorXd& values, double rare_fraction);

}  // namespace freeform_inspection
