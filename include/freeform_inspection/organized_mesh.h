// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include "freeform_inspection/types.h"

/// @file organized_mesh.h
/// Organized clouds (range images from structured-light or laser-line scanners) carry their
/// connectivity in the grid: neighbouring pixels are neighbouring surface points, unless the
/// surface jumps (an occlusion edge). Triangulating on the grid gives the scan a mesh for free.

namespace freeform_inspection {

struct OrganizedMeshConfig {
  double max_edge_ratio = 5.0;  ///< edges longer than this × the median grid edge are occlusion
                                ///< jumps, not surface: triangles using them are dropped [-]
};

/// @brief Two triangles per grid cell whose corners are finite (one where only three are),
/// choosing the shorter diagonal, oriented towards the sensor (which looks along +z of the
/// points' frame from the origin, like a camera), skipping cells that cross an occlusion edge.
/// @param points width·height points, row-major, NaN where nothing was measured.
/// @return faces indexing `points` (non-finite points are used by no face); empty when the grid
/// holds fewer than three finite neighbours.
Triangles triangulateOrganizedGrid(const Points& points,
                                   int width,
                                   int height,
                                   const OrganizedMeshConfig& config);

}  // namespace freeform_inspection
