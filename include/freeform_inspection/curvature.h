// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <vector>

#include "freeform_inspection/mesh_adjacency.h"
#include "freeform_inspection/types.h"

/// @file curvature.h
/// Per-point curvature, the input of the multiscale descriptor (paper §2.1, §3.2).
///
/// Sign convention: mean curvature H is positive where the surface is convex seen from outside
/// (a sphere with outward normals has H = +1/R), negative where it is concave; H = (k1 + k2)/2.

namespace freeform_inspection {

/// Discrete mean-curvature estimator on meshes.
enum class MeanCurvatureMethod {
  kAngleBased,  ///< paper eq. 3: (1/4 Σ |e_j| γ_j) / (A/3), γ_j the signed dihedral angle
  kCotangent,   ///< paper eq. 4–5: |cotangent Laplacian| / 2 over the Voronoi area, sign from
                ///< the vertex normal (Meyer et al.)
};

struct MeshCurvatureConfig {
  MeanCurvatureMethod method = MeanCurvatureMethod::kAngleBased;  ///< paper default
};

/// Per-vertex curvature of a mesh or a cloud.
struct CurvatureResult {
  Status status;                 ///< kDegenerateInput when no vertex has a usable neighbourhood
  std::vector<double> mean;      ///< [1/m] H per point (0 where undefined, e.g. isolated points)
  std::vector<double> gaussian;  ///< [1/m^2] K per point (paper eq. 2; meshes only, else empty)
  std::vector<double> area;      ///< [m^2] area each point stands for (A/3 on meshes); sums to
                                 ///< about the surface area
  Points normals;                ///< unit normal per point, oriented outward (area-weighted face
                                 ///< normals on meshes; estimated and oriented on clouds)
  Points on_plane;  ///< clouds: each point moved along its normal onto the least-squares plane
                    ///< of its neighbourhood, the noise averaged out (empty on meshes)
  /// Clouds without given normals: the sign of some normals came from the centroid vote (no
  /// visibility evidence), so a whole view may be inside out (its H negated).
  bool signs_guessed = false;
};

/// @brief Curvature of every vertex of a mesh (paper eq. 2 and eq. 3, or eq. 4–5).
/// Boundary vertices use the faces they have (their H is less reliable); vertices used by no
/// face get H = 0 and area 0.
CurvatureResult computeMeshCurvature(const Points& vertices,
                                     const Triangles& faces,
                                     const MeshAdjacency& adjacency,
                                     const MeshCurvatureConfig& config);

/// Curvature estimator on unorganized point clouds.
struct CloudCurvatureConfig {
  int neighbours = 24;  ///< k nearest neighbours of the curvature fit (and the PCA normal)
  /// [m] the cloud's measured noise σ (0: unknown); widens the depth tolerance of the
  /// visibility votes that orient normals when none are given
  double noise_sigma = 0.0;
};

/// @brief Curvature of every point of a cloud without faces: the shape operator S fitted by
/// least squares to the normal changes towards the k nearest neighbours (n_j − n_i ≈ S·(p_j −
/// p_i) in the tangent plane; neighbours whose normal turned by more than 120° are on the other
/// side of a thin wall and skipped) gives H = trace(S)/2. Normals are PCA normals of the
/// neighbourhood, oriented by the scan's normals where given (`normals` non-empty, one per
/// point; zero = unknown). Without given normals, points whose side visibility from outside
/// tells (a closed scan: seen from outside only) fix theirs; the rest are propagated over the
/// kNN graph along the surface, and a component with no fixed point is flipped so that most
/// normals point away from its centroid. Each
/// point's area is π d_k² / k, d_k the distance to its k-th neighbour.
CurvatureResult computeCloudCurvature(const Points& points,
                                      const Points& normals,
                                      const CloudCurvatureConfig& config);

}  // namespace freeform_inspection
