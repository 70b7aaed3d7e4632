// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>

#include <Eigen/Geometry>

#include "freeform_inspection/chord_error.h"
#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/surface_graph.h"

/// @file surface_support.h
/// How much of the scan's *surface* a pose puts on the CAD. ICP fitness counts every point, so
/// it cannot tell a scan with 20 % scattered outliers (fitness 0.8, right pose) from a flipped
/// or slid pose that leaves a quarter of the part's surface hanging off the CAD (fitness 0.76).
/// Scattered outliers have no surface neighbours; a surface left off the CAD is a connected
/// patch of well-linked cells. Counting only linked cells separates the two.

namespace freeform_inspection {

/// @brief Share of the scan's surface that lies within `band` [m] of the CAD surface at
/// `T_cad_scan`: over up to `count` cells spread evenly over the cell list, those with at least
/// `min_links` graph neighbours (the surface; isolated outliers have none), one real scan point
/// each (a centroid would sit inside a curved surface by its sagitta). 1 when no cell qualifies.
/// @param scan_points the points the graph's `point_cell` indexes.
/// @param curved when active, the band is about the curve the CAD's faces stand for.
double surfaceOnCad(const SurfaceGraph& scan,
                    const Points& scan_points,
                    const MeshQuery& cad,
                    const Eigen::Isometry3d& T_cad_scan,
                    double band,
                    std::size_t count,
                    int min_links = 3,
                    const CurvedSurface& curved = CurvedSurface());

}  // namespace freeform_inspection
