// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "freeform_inspection/types.h"

/// @file correspondence.h
/// Correspondence search (paper §2.5, §3.5, first step): for every scan feature, the CAD cells
/// whose descriptors agree with it over the scales. The triangle (pairwise-distance) check that
/// prunes them runs in global_registration.h, where the triplets are formed.

namespace freeform_inspection {

/// Candidate-search settings.
struct CorrespondenceConfig {
  /// Mean |ΔV_k| over the K scales within which a CAD cell is a candidate. The paper's "2 %"
  /// read as 2 % of the descriptor's range [0, 1].
  double descriptor_tolerance = 0.02;
  int min_candidates = 12;  ///< the nearest in descriptor space are kept even beyond the tolerance
  int max_candidates = 32;  ///< at most this many per feature, best agreement first
  /// When no pose explains the scan with max_candidates, the search is run once more with this
  /// many per feature (the true place can rank lower on a partial or noisy scan); a value not
  /// above max_candidates turns the second search off.
  int retry_candidates = 96;
  /// Candidates of one feature are at least this many CAD cells apart, so a ridge of similar
  /// descriptors yields candidates spread along it rather than a clump at one end.
  double separation_cells = 1.5;
};

/// @brief One message per invalid field; empty when valid.
std::vector<std::string> validate(const CorrespondenceConfig& config);

/// The CAD candidates of one scan feature.
struct FeatureCandidates {
  int feature = -1;                         ///< scan cell of the feature
  std::vector<int> cad;                     ///< CAD cells, best agreement first
  std::vector<double> descriptor_distance;  ///< mean |ΔV_k| of each
};

/// Candidates of all features.
struct CorrespondenceResult {
  Status status;
  std::vector<FeatureCandidates> features;  ///< one entry per feature, same order
  std::size_t candidates = 0;               ///< total over the features
};

/// @brief Finds candidates.
/// @param scan_values scan cells × K, `features` index its rows
/// @param cad_values CAD cells × K
/// @param cad_positions CAD cell centres [m]
/// @param cell_size [m] surface-graph cell size (the descriptors' spatial resolution)
CorrespondenceResult findCandidates(const Eigen::MatrixXd& scan_values,
                                    const std::vector<int>& features,
                                    const Eigen::MatrixXd& cad_values,
                                    const Points& cad_positions,
                                    double cell_size,
                                    const CorrespondenceConfig& config);

}  // namespace freeform_inspection
