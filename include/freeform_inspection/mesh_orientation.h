// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "freeform_inspection/types.h"

/// @file mesh_orientation.h
/// Consistent outward winding of a CAD mesh, so the signed deviation has one meaning
/// everywhere, and the border edges of open surfaces.

namespace freeform_inspection {

/// What orientOutward() changed.
struct OrientationResult {
  std::size_t components = 0;           ///< connected pieces (faces joined by manifold edges)
  std::size_t flipped_faces = 0;        ///< faces whose winding was reversed
  std::size_t reversed_components = 0;  ///< whole pieces turned inside out → outside out
};

/// @brief Makes the winding consistent across every manifold edge, then turns each piece so
/// its normals point out: closed pieces by the sign of their enclosed volume, open pieces
/// (sheets, no inside) to agree with the majority of their original area, which is how the
/// exporter meant them. Face normals are recomputed.
OrientationResult orientOutward(TriangleMesh* mesh);

/// @brief Per face, bit e set when the edge from corner e to corner e+1 is used by no other
/// face (a border of an open surface). Empty when the mesh has no border.
std::vector<std::uint8_t> borderEdgeMasks(const TriangleMesh& mesh);

}  // namespace freeform_inspection
