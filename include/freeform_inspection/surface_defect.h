// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cmath>

#include <Eigen/Core>

/// @file surface_defect.h
/// A spherical-cap dent or bump on a surface, as the virtual scanner and the tests inject it.

namespace freeform_inspection {

/// A spherical cap of base radius `radius` and height |depth| pressed into (depth < 0, a dent)
/// or raised out of (depth > 0, a bump) the surface around `centre`.
struct SurfaceDefect {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< [m] a point on the nominal surface
  double radius = 0.0;                               ///< [m] base radius of the cap
  double depth = 0.0;  ///< [m] signed height at the centre: < 0 dent, > 0 bump
};

/// @brief Displacement along the outward surface normal that the defect adds at a surface
/// point: `depth` at the centre, falling to 0 at `radius` along the sphere of the cap, 0
/// beyond. Distance is measured in 3-D (the defect is small against the surface's curvature).
inline double defectDisplacement(const SurfaceDefect& defect, const Eigen::Vector3d& point) {
  const double h = defect.depth < 0.0 ? -defect.depth : defect.depth;
  if (!(defect.radius > 0.0) || !(h > 0.0)) {
    return 0.0;
  }
  const double rho2 = (point - defect.centre).squaredNorm();
  if (rho2 >= defect.radius * defect.radius) {
    return 0.0;
  }
  const double sphere = (defect.radius * defect.radius + h * h) / (2.0 * h);  // cap's sphere
  const double height = h - (sphere - std::sqrt(sphere * sphere - rho2));
  return defect.depth < 0.0 ? -height : height;
}

}  // namespace freeform_inspection
