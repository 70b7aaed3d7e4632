// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/descriptor.h"
#include "freeform_inspection/mesh_query.h"

/// @file symmetry.h
/// Rigid self-symmetries of the CAD model, found once per model by registering the model to
/// itself with the same global stage the scans go through. A pose T of a scan and S·T (S a
/// symmetry) explain a full scan equally well; the pipeline scores both so that a symmetric part
/// is reported as ambiguous instead of with a confident, possibly flipped, pose, and so that the
/// twin that a partial view does distinguish is found even when the triplets missed it.

namespace freeform_inspection {

/// A motion S of the CAD frame that maps the model (nearly) onto itself.
struct Symmetry {
  Eigen::Isometry3d S = Eigen::Isometry3d::Identity();
  double score = 0.0;  ///< share of the model's cells that S maps onto the model surface
};

/// Self-match score a motion needs to count as a symmetry of the model. A scan is a view: a
/// motion that lays 40 % of the model onto itself can lay a whole view onto the model, so the
/// twins the pipeline tries include such partial self-matches (docs/registration.md).
constexpr double kDefaultSymmetryScore = 0.4;

/// @brief Symmetries other than the identity whose self-match score is at least `min_score`,
/// best first. Deterministic.
/// @param cad the model's descriptors (cells, values, radii)
/// @param cell_size [m] surface-graph cell size; `diagonal` [m] the model's L
std::vector<Symmetry> findSymmetries(const DescriptorResult& cad,
                                     const MeshQuery& query,
                                     double cell_size,
                                     double diagonal,
                                     double min_score = kDefaultSymmetryScore);

/// @brief The 23 turns (quarter, half and third) that map a cube set along the principal axes of
/// `graph` (area-weighted, through its centroid) onto itself, the identity left out. Where a pose
/// leaves much of a view off the CAD, these are the confusions of a blocky part that its symmetries
/// need not cover (a bar's section turned about its diagonal). Empty for a graph without area.
std::vector<Eigen::Isometry3d> principalFrameTurns(const SurfaceGraph& graph);

/// @brief The same 23 turns of a cube set along the principal axes of `graph`'s cell normals
/// (area-weighted scatter, through the centroid of its cells): a sheet part's wall and face
/// directions, about which (and their bisectors) its near-symmetries turn even where unequal
/// flanges or legs tilt the axes of its spread. Empty for a graph without area or normals.
std::vector<Eigen::Isometry3d> normalFrameTurns(const SurfaceGraph& graph);

}  // namespace freeform_inspection
