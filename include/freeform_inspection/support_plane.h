// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "freeform_inspection/types.h"

/// @file support_plane.h
/// The table or fixture plate a part rests on, found in the scan and removed before the
/// registration. A scanner sees the support around the part, often in more pixels than the part
/// itself, and a pose must explain most of the scan (GlobalRegistrationConfig::min_surface_on_cad).
///
/// The test needs no model of the support: no two points of the part lie farther apart than the
/// CAD's bounding-box diagonal L, so a connected planar patch of the scan wider than L (plus the
/// noise) cannot be a face of the part. Such a plane is the support; its points within the noise
/// band, and any behind it, are removed. A planar face of the part is never wider than L and is
/// kept, whatever its share of the scan; a support seen only as a narrow strip around the part is
/// kept too (the registration then fails safely, and a crop is needed). The test holds only for
/// a band thinner than the part: a band as thick as a slender part holds all of it and, with
/// stray points about it, reaches wider than L. So the band never exceeds a quarter of the
/// part's thickness (its extent along its axis of least spread).

namespace freeform_inspection {

/// Settings of the support removal (PipelineConfig::support; YAML section `support`).
struct SupportConfig {
  bool remove = true;  ///< look for supports at all
  int max_planes = 2;  ///< supports removed at most (a table and a fixture plate, say)
  /// A plane holding fewer than this share of the scan's points is left alone: the registration
  /// tolerates that much foreign surface.
  double min_share = 0.05;
  /// Half-width of a support's band in units of the scan's noise σ (at least 0.1 % of L).
  double band_sigmas = 4.0;
};

/// @brief One message per invalid field; empty when valid.
std::vector<std::string> validate(const SupportConfig& config);

/// A support found in the scan.
struct SupportPlane {
  /// n·x + d = 0 in the scan frame, n unit and pointing to the part's side
  Eigen::Vector4d plane = Eigen::Vector4d::Zero();
  std::size_t points = 0;  ///< scan points removed with it
  double width = 0.0;      ///< [m] width of its largest connected patch, over L in the test
};

/// Which points of a scan belong to supports.
struct SupportResult {
  std::vector<SupportPlane> planes;  ///< in the order found (most points first)
  std::vector<char> on_support;      ///< per point: 1 when it lies on one of `planes`
  std::size_t removed = 0;           ///< points marked in on_support

  /// One line per plane for the inspection's warnings.
  std::vector<std::string> describe() const;
};

/// @brief Finds the supports of a scan: the dominant plane (RANSAC on an even subsample, the
/// band ±band_sigmas·σ), then the width of the largest connected patch of its points on a grid
/// in the plane; wider than `part_diameter` plus the grid's resolution, it is a support, and
/// its band and everything behind it (away from the side most of the other points are on) are
/// marked. The next plane is tried on the rest. Deterministic.
/// @param points finite scan points [m]
/// @param noise_sigma [m] the scan's measured noise (scan_noise.h), 0 when unknown
/// @param part_diameter [m] the CAD's bounding-box diagonal L
/// @param part_thickness [m] the CAD's principalThickness() (mesh.h): the band is at most a
/// quarter of it
SupportResult findSupports(const Points& points,
                           double noise_sigma,
                           double part_diameter,
                           double part_thickness,
                           const SupportConfig& config);

}  // namespace freeform_inspection
