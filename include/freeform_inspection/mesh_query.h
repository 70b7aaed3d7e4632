// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "freeform_inspection/types.h"

/// @file mesh_query.h
/// Exact geometric queries on a triangle mesh (the CAD): closest point on the triangles with a
/// signed distance, and ray casting. Embree builds and traverses the acceleration structure; we
/// only supply the exact point–triangle distance.

namespace freeform_inspection {

/// The closest point of the mesh surface to a query point.
struct ClosestPoint {
  bool found = false;                                ///< false: nothing within max_distance
  int face = -1;                                     ///< triangle holding the closest point
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< [m] closest point on that triangle
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit outward face normal there
  double distance = std::numeric_limits<double>::infinity();  ///< [m] unsigned
  /// [m] signed: positive outside the material. The sign comes from the angle-weighted
  /// pseudo-normal of the closest feature (face, edge or vertex), so it is right at edges and
  /// corners of a closed, outward-oriented mesh.
  double signed_distance = std::numeric_limits<double>::infinity();
};

/// The first surface hit along a ray.
struct RayHit {
  bool hit = false;
  int face = -1;
  double t = std::numeric_limits<double>::infinity();  ///< [m] distance along the unit ray
  Eigen::Vector3d point = Eigen::Vector3d::Zero();     ///< [m]
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();    ///< unit outward face normal
};

/// Closest-point and ray queries on one mesh. Built once (the mesh is copied); const queries are
/// thread-safe.
class MeshQuery {
 public:
  explicit MeshQuery(const TriangleMesh& mesh);
  ~MeshQuery();
  MeshQuery(const MeshQuery&) = delete;
  MeshQuery& operator=(const MeshQuery&) = delete;

  /// ok, or why the structure could not be built (no faces, non-finite vertices, Embree error).
  const Status& status() const;

  /// @brief Closest point of the surface to `query`, if one lies within `max_distance` [m].
  ClosestPoint closest(const Eigen::Vector3d& query,
                       double max_distance = std::numeric_limits<double>::infinity()) const;

  /// @brief closest() among the faces that face the way `normal` does: outward normals within
  /// the angle whose cosine is `min_cos` (compared as lines when `oriented` is false). Whether
  /// some surface turned that way lies within `max_distance`: a noisy point on a wall thinner
  /// than its noise is often nearer the wall's far side, which a plain closest() would report.
  ClosestPoint closestFacing(const Eigen::Vector3d& query,
                             const Eigen::Vector3d& normal,
                             double min_cos,
                             bool oriented,
                             double max_distance) const;

  /// @brief closest() for many points (OpenMP parallel; results in input order).
  std::vector<ClosestPoint> closest(
      const Points& queries, double max_distance = std::numeric_limits<double>::infinity()) const;

  /// @brief closest() for many points, each search starting from a face likely to be near
  /// (`hints[i]`, −1 for none; e.g. the face of the previous ICP iteration): its distance bounds
  /// the search from the start. The same results as without hints, found faster.
  std::vector<ClosestPoint> closest(const Points& queries,
                                    double max_distance,
                                    const std::vector<int>& hints) const;

  /// @brief closestFacing() for many points (`normals[i]` for `queries[i]`; a zero normal
  /// accepts every face), each search starting from `hints[i]` when it is a face (−1: none).
  std::vector<ClosestPoint> closestFacing(const Points& queries,
                                          const Points& normals,
                                          double min_cos,
                                          bool oriented,
                                          double max_distance,
                                          const std::vector<int>& hints) const;

  /// @brief First hit of the ray origin + t·direction for t in (t_min, t_max].
  /// @param direction need not be unit; t is measured in metres along its unit vector.
  RayHit castRay(const Eigen::Vector3d& origin,
                 const Eigen::Vector3d& direction,
                 double t_min = 0.0,
                 double t_max = std::numeric_limits<double>::infinity()) const;

  /// The copied mesh, with `face_normals` recomputed from the winding (zero for degenerate
  /// faces) when status() is ok.
  const TriangleMesh& mesh() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace freeform_inspection
