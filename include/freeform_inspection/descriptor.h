// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "freeform_inspection/curvature.h"
#include "freeform_inspection/surface_graph.h"
#include "freeform_inspection/types.h"

/// @file descriptor.h
/// Multiscale integral volume descriptor (paper §2.3, §3.3):
///   V_k(p) = 1/2 − (3/16) · H̃_k(p) · r_k                                     (eq. 11)
/// with H̃_k the geodesically weighted mean curvature over the geodesic ball of radius r_k
/// (eq. 6–7), r_k = k · r_max / K. The radii come from the CAD model (r_max = 0.1 · L_max, L_max
/// its bounding-box diagonal) and the same absolute radii are used on the scan, so a partial
/// scan gets the same descriptor as the full part.

namespace freeform_inspection {

/// Descriptor settings (paper defaults).
struct DescriptorConfig {
  int scales = 6;                     ///< K, number of kernel radii (paper: 6)
  double max_radius_ratio = 0.1;      ///< r_max / L_max, L_max = CAD bounding-box diagonal (paper)
  double cell_ratio = 0.6;            ///< surface-graph cell size / r_1: resolution of the balls
  double coarse_ball_cells = 0.0;     ///< > 0: a scale is averaged on the coarsest graph (cells
                                      ///< 2^l × the finest) whose cells are at most r_k / this
                                      ///< wide, then interpolated to the finest cells (2.4:
                                      ///< descriptors ~3× faster, registration ~1 % less
                                      ///< successful, docs/descriptors.md); 0: every scale on
                                      ///< the finest cells
  int cloud_edge_neighbours = 8;      ///< clouds: kNN surface edges per point
  double cloud_edge_spacings = 3.0;   ///< clouds: surface edges up to max(r_1, this × the
                                      ///< median point spacing), so sparse scans stay joined
  double cloud_thinning_ratio = 0.1;  ///< clouds: one point per voxel of this × r_1 is
                                      ///< analysed (denser sampling adds cost, not detail);
                                      ///< 0 analyses every point
  std::size_t max_analysed_points = 100000;  ///< clouds: at most this many of the thinned
                                             ///< points are analysed, evenly spread (a 1M-point
                                             ///< scan costs a 100k one); 0 = no cap
  double noise_fit_multiple = 3.0;     ///< clouds: the curvature fit's neighbourhood reaches at
                                       ///< least this × the scan's measured noise σ (more
                                       ///< neighbours than cloud_neighbours on a noisy scan)
  int max_cloud_neighbours = 256;      ///< clouds: ... with at most this many neighbours
  int noise_fit_budget = 128;          ///< clouds: a noisy cloud with more points than this
                                       ///< within noise_fit_multiple · σ is analysed on a random
                                       ///< share with about this many there (at least 4 per cell
                                       ///< area); 0 analyses every thinned point
  MeshCurvatureConfig mesh_curvature;  ///< one-ring curvature on meshes
  CloudCurvatureConfig cloud_curvature;  ///< local-quadric curvature on clouds
};

/// @brief Checks the settings; one message per bad field, empty when valid.
std::vector<std::string> validate(const DescriptorConfig& config);

/// @brief r_k = k · r_max / K for k = 1..K, r_max = max_radius_ratio · `cad_diagonal` [m].
std::vector<double> kernelRadii(double cad_diagonal, const DescriptorConfig& config);

/// @brief Graph level of every scale: scale k is averaged on cells 2^level × `cell` wide, the
/// coarsest level whose cells are at most r_k / `ball_cells` wide (level 0 for every scale when
/// `ball_cells` is 0). With cells of 0.6 r_1 and 2.4 cells, K = 6 gives 0 0 1 1 1 2.
std::vector<int> scaleLevels(const std::vector<double>& radii, double cell, double ball_cells);

/// Descriptors of one surface (the CAD or a scan).
struct DescriptorResult {
  Status status;                    ///< kDegenerateInput when the surface has no usable area
  std::vector<double> radii;        ///< [m] r_k
  CurvatureResult curvature;        ///< curvature of the analysed points (see below)
  std::vector<int> analysed;        ///< indices of the points the curvature belongs to: all of
                                    ///< them, or one per voxel of a thinned dense cloud
  SurfaceGraph graph;               ///< cells on which the balls were grown
  Eigen::MatrixXd cell_values;      ///< cells × K: V_k of every cell
  Eigen::MatrixXd cell_curvature;   ///< cells × K: H̃_k of every cell [1/m]
  std::vector<int> representative;  ///< thinned clouds: per point, its entry in `analysed` (its
                                    ///< own, or the analysed point it joined); else empty
  int cloud_neighbours = 0;         ///< clouds: neighbours of the curvature fit (0 on meshes)
  Points on_quadric;                ///< clouds whose fit grew (fitGrew()): each analysed point
                                    ///< moved onto its fit neighbourhood's quadric; else empty
  std::vector<std::string> warnings;

  /// V_k of point i: the value of its cell (NaN for a point without area).
  double value(std::size_t point, int scale) const;

  /// True for a cloud whose curvature fit grew with its measured noise: then the points moved
  /// onto their neighbourhood planes (curvature.on_plane) bin the cells, and the points moved
  /// onto their neighbourhood quadrics (on_quadric) carry the scan's ICP, both with the noise
  /// averaged out.
  bool fitGrew(const DescriptorConfig& config) const;

  /// Every one of `points` (those the descriptors were computed from) moved onto the surface
  /// fitted around its analysed point: `on_quadric` for the analysed points, the plane through
  /// it with that point's normal for the points that joined them. Empty unless on_quadric is set.
  Points onFittedSurfaces(const Points& points) const;

  /// The normal of each of the `count` points the descriptors were computed from: its analysed
  /// point's (curvature.normals). Empty when the curvature has no normals for them.
  Points pointNormals(std::size_t count) const;
};

/// @brief Computes V_k for every point of a mesh (faces non-empty) or a cloud (faces empty).
/// A dense cloud is thinned first (cloud_thinning_ratio); every point still gets the value of
/// the cell its voxel's representative fell in.
/// @param normals optional (empty or one per point): scanner normals for clouds.
/// @param radii kernel radii from kernelRadii() of the CAD model.
/// @param noise_sigma [m] the cloud's measured noise (scan_noise.h), 0 when unknown: sizes the
/// curvature fit of a noisy cloud (DescriptorConfig::noise_fit_multiple). Meshes ignore it.
DescriptorResult computeDescriptors(const Points& points,
                                    const Triangles& faces,
                                    const Points& normals,
                                    const std::vector<double>& radii,
                                    const DescriptorConfig& config,
                                    double noise_sigma = 0.0);

}  // namespace freeform_inspection
