// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <array>
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
  /// Per face, q_ij = (n_j − n_i)·(x_j − x_i) of its edges (corners 0–1, 1–2, 2–0) with the
  /// curve's normals n at its corners x: positive where the curve bulges out of the face
  /// (convex), negative where it sinks below it; 0 where the face is not a curve's facet.
  std::vector<std::array<double, 3>> bulge;
};

/// The curved surface a coarse CAD's faces stand for (chord_error.h) as ICP's target: each
/// closest point on a face moves out along its normal by `share` × the face's bulge there. A
/// scan of a real part follows the curve; a scan made from the mesh itself follows the faces
/// (ICP estimates the share with the pose when asked). Inactive by default: the faces.
struct CurvedSurface {
  const ChordError* chord = nullptr;
  double share = 0.0;     ///< 0: the faces; 1: the curve
  bool estimate = false;  ///< refinePose() fits the share with the pose (IcpResult::curve_share)
  bool active() const { return chord != nullptr && share > 0.0; }
};

/// @brief Estimates the chord error of every face of `mesh` (face normals as the mesh keeps
/// them, computed when missing). Linear in the faces (a 58k-face blade: a few milliseconds).
ChordError estimateChordError(const TriangleMesh& mesh);

/// @brief How far the curved surface lies outside face `face` of `mesh` (along its outward
/// normal) at `point` on the face [m]: ½ Σ λ_i λ_j q_ij over its edges, λ the point's
/// barycentric coordinates; exact for a quadric surface. 0 when the estimate has no bulges.
double bulgeAt(const ChordError& error,
               const TriangleMesh& mesh,
               int face,
               const Eigen::Vector3d& point);

}  // namespace freeform_inspection
