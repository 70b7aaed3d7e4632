// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <vector>

#include <Eigen/Core>

#include "freeform_inspection/types.h"

/// @file blade_geometry.h
/// Parametric turbine blade used as the shipped sample part (data/blade/).
///
/// The blade is a stack of closed cross-sections along +z: a superellipse root platform, a short
/// smoothstep fillet zone and a twisted, tapered NACA-4-digit-style airfoil. Every section has
/// the same number of points in the same order, so consecutive sections join with quads and the
/// bottom and top sections are closed by caps made of strips between the lower and upper side at
/// matching chord stations (the strips of the wide platform are cut into rows). The result is a
/// closed, outward-oriented, genus-0 solid.
///
/// Unlike the rest of the package, everything here is in MILLIMETRES, because CAD files are:
/// generateBlade() returns a TriangleMesh whose vertices are in mm (not the [m] that types.h
/// documents); load the written STL with scale 0.001.

namespace freeform_inspection {
namespace tools {

/// Shape and sampling of the blade. Lengths in millimetres, angles in degrees.
struct BladeParameters {
  // Airfoil, interpolated linearly from the root section (span fraction 0) to the tip (1).
  double span_mm = 120.0;                   ///< [mm] airfoil height, root section to tip
  double root_chord_mm = 45.0;              ///< [mm] chord length at the root section
  double tip_chord_mm = 30.0;               ///< [mm] chord length at the tip
  double root_max_camber = 0.06;            ///< [chord fraction] NACA "m" at the root
  double tip_max_camber = 0.02;             ///< [chord fraction] NACA "m" at the tip
  double camber_position = 0.40;            ///< [chord fraction] NACA "p", x of max camber
  double root_max_thickness = 0.14;         ///< [chord fraction] NACA "t" at the root
  double tip_max_thickness = 0.08;          ///< [chord fraction] NACA "t" at the tip
  double trailing_edge_thickness_mm = 0.6;  ///< [mm] where the trailing edge rounding starts
  double stacking_position = 0.35;       ///< [chord fraction] stacking axis, from the leading edge
  double root_stagger_deg = 10.0;        ///< [deg] chord angle from +x about +z at the root
  double tip_stagger_deg = -35.0;        ///< [deg] chord angle from +x about +z at the tip
  double tip_sweep_mm = 4.0;             ///< [mm] +x shift of the tip stacking point (quadratic)
  double tip_lean_mm = -2.5;             ///< [mm] +y shift of the tip stacking point (quadratic)
  double leading_edge_clustering = 1.0;  ///< [0..1] 1: cosine chord stations, 0: uniform

  // Root platform: superellipse |x/a|^p + |y/b|^p = 1, rotated and offset from the stacking axis
  // so that the part has no symmetry (it is a pose registration sample).
  double platform_length_mm = 70.0;    ///< [mm] 2a, along the platform's own x axis
  double platform_width_mm = 30.0;     ///< [mm] 2b, along the platform's own y axis
  double platform_exponent = 4.0;      ///< [-] superellipse exponent p (2: ellipse)
  double platform_height_mm = 15.0;    ///< [mm] z from the bottom face to the fillet start
  double platform_angle_deg = 4.0;     ///< [deg] platform x axis from +x about +z
  double platform_offset_x_mm = 3.0;   ///< [mm] platform centre minus stacking axis, x
  double platform_offset_y_mm = -2.0;  ///< [mm] platform centre minus stacking axis, y
  double fillet_height_mm = 4.0;       ///< [mm] smoothstep blend from platform to root airfoil

  // Sampling. A section has 2 * (chord_stations - 1) points; the mesh has
  // (platform_intervals + fillet_intervals + airfoil_intervals + 1) sections plus the interior
  // points of the two caps. The defaults give about 7,300 vertices.
  int chord_stations = 41;     ///< [count] chord stations, leading and trailing edge included
  int platform_intervals = 3;  ///< [count] section gaps across the platform height
  int fillet_intervals = 4;    ///< [count] section gaps across the fillet height
  int airfoil_intervals = 76;  ///< [count] section gaps across the airfoil span
};

/// @brief The default shape sampled about four times finer (twice along both directions).
BladeParameters fineBladeParameters();

/// @brief kInvalidInput naming the first field that is out of range, else success.
Status validateBladeParameters(const BladeParameters& parameters);

/// Where things are in the generated mesh: section k owns vertices
/// [k * points_per_section, (k + 1) * points_per_section), in the order leading edge, lower side
/// towards the trailing edge, trailing edge, upper side back towards the leading edge
/// (counter-clockwise seen from +z). The interior points of the bottom cap, then of the top cap,
/// follow the last section.
struct BladeLayout {
  int points_per_section = 0;        ///< [count] 2 * (chord_stations - 1)
  int leading_edge_point = 0;        ///< index of the leading edge within a section
  int trailing_edge_point = 0;       ///< index of the trailing edge within a section
  int root_section = 0;              ///< first pure airfoil section (end of the fillet)
  std::vector<double> section_z_mm;  ///< [mm] height of every section, bottom to top
};

/// @brief Section heights and point indexing of the mesh generateBlade() builds.
BladeLayout bladeLayout(const BladeParameters& parameters);

/// @brief Closed outline of the cross-section at height z, in layout order.
/// @param z_mm [mm] from 0 (platform bottom) to the tip height.
std::vector<Eigen::Vector2d> sectionOutline(const BladeParameters& parameters, double z_mm);

/// @brief Builds the closed blade mesh in MILLIMETRES, face normals included.
/// @pre validateBladeParameters(parameters).ok(); otherwise an empty mesh is returned.
TriangleMesh generateBlade(const BladeParameters& parameters);

}  // namespace tools
}  // namespace freeform_inspection
