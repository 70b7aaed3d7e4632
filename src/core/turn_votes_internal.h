// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// Translations for turned starts, voted by the feature candidates (pipeline.cpp's retries).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/correspondence.h"
#include "freeform_inspection/surface_graph.h"

namespace freeform_inspection {
namespace internal {

struct TurnVoteConfig {
  double bin_cells = 2.0;       ///< width of a vote bin [cells]
  int min_features = 3;         ///< distinct features a bin needs, as many as a triplet has
  std::size_t max_starts = 32;  ///< best supported starts kept
};

/// @brief Starts with the rotations of `turned` (poses T_cad_scan) and the translations the
/// feature candidates vote for. Each pair (scan feature, CAD candidate cell) votes for the
/// translation that lays the one on the other under the turn's rotation; the bin of width
/// `config.bin_cells` · `cell` with votes from the most distinct features gives the turn's start,
/// if at least `config.min_features` agree (bins on two grids half a bin apart, so a cluster on a
/// bin's edge is not split). Best supported first, poses not separate from a better one
/// (separatePoses at `reference`, scan frame) left out. Deterministic.
std::vector<Eigen::Isometry3d> votedTurnStarts(const std::vector<Eigen::Isometry3d>& turned,
                                               const std::vector<CorrespondenceResult>& candidates,
                                               const SurfaceGraph& scan,
                                               const SurfaceGraph& cad,
                                               const Eigen::Vector3d& reference,
                                               double cell,
                                               const TurnVoteConfig& config = TurnVoteConfig());

}  // namespace internal
}  // namespace freeform_inspection
