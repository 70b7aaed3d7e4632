// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <vector>

#include <Eigen/Core>

#include "freeform_inspection/types.h"

/// @file chord_error.h
/// How far a CAD mesh's flat faces may lie from the curved surface they stand for: the chord
/// error of its tessellation, estimated from the mesh alone. A scan of a good part lies on the
/// curved surface, so where the CAD was exported coarsely the deviation map shows the facets
/// (a blade's platform ends in data/blade/blade.stl: 0.63 mm bumps on a perfect scan). The
/// inspection reports this estimate beside each defect region and warns when it is a sizeable
/// share of the tolerance band (docs/inspection.md, "The CAD's chord error").
///
/// A mesh cannot say whether a small turn between two faces is a facet of a curve or an edge
/// drawn by the designer (a 3° draft). Turns count as a curve's only where the facets show it:
/// a flat facet (coplanar faces) that turns the same way on opposite sides, by less than a
/// crease, towards facets of comparable width (a cylinder's facets; not a flat face between two
/// fillets, not a draft face or a shallow roof, which turn on one side only). Across such turns
/// each vertex gets the mean normal of the faces about it, and each face's error follows from
/// how those normals turn along its edges, exact for a quadric surface sampled at its vertices.

namespace freeform_inspection {

/// The estimate, per face and overall.
struct ChordError {
  /// [m] per face: estimated largest distance between the face and the curved surface it
  /// approximates; 0 on flat faces and where every turn is a drawn edge.
  std::vector<double> face;
  double max = 0.0;                                  ///< [m] largest over the faces
  Eigen::Vector3d max_at = Eigen::Vector3d::Zero();  ///< [m] centroid of that face
  double curved_area_share = 0.0;  ///< share of the area read as facets of a curve
};

/// @brief Estimates the chord error of every face of `mesh` (face normals as the mesh keeps
/// them, computed when missing). Linear in the faces (a 58k-face blade: a few milliseconds).
ChordError estimateChordError(const TriangleMesh& mesh);

}  // namespace freeform_inspection
