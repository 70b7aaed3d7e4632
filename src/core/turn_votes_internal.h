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

/// Settings of surfaceVotedTurnStarts().
struct SurfaceVoteConfig {
  std::size_t scan_cells = 64;         ///< scan cells that vote (every n-th)
  std::size_t cad_cells = 4096;        ///< CAD cells they may land on (every n-th)
  double normal_tolerance_deg = 25.0;  ///< a pair's normals agree within this
  double bin_cells = 4.0;              ///< width of a vote bin [cells]
  double min_share = 0.5;              ///< of the voting cells the densest bin needs
  std::size_t max_starts = 8;          ///< best supported starts kept
};

/// @brief Starts with the rotations of `turned` (poses T_cad_scan) and the translation the scan's
/// surface votes for: under each rotation, every sampled scan cell votes for the translations
/// that lay it on a sampled CAD cell whose normal agrees with its own (either sign unless the
/// scan's normals are `oriented`, pointing out of the material), and the bin with votes from
/// the most distinct scan cells gives the start, if it holds `config.min_share` of them (a
/// generalised Hough transform over translations). Unlike votedTurnStarts() it needs no feature
/// whose candidates hold the right CAD cell: a machined block's view with its legs swapped had
/// none (docs/registration.md, "Parts never seen"). Best supported first, poses not
/// separate from a better one left out. Deterministic whatever the thread count.
std::vector<Eigen::Isometry3d> surfaceVotedTurnStarts(
    const std::vector<Eigen::Isometry3d>& turned,
    const SurfaceGraph& scan,
    const SurfaceGraph& cad,
    bool oriented,
    const Eigen::Vector3d& reference,
    double cell,
    const SurfaceVoteConfig& config = SurfaceVoteConfig());

}  // namespace internal
}  // namespace freeform_inspection
