// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/view_hints.h"

#include <Eigen/Geometry>

namespace freeform_inspection {

ViewHints rangeImageViewHints(const Scan& scan, double min_agreement) {
  ViewHints hints;
  double facing = 0.0;
  double total = 0.0;
  for (const auto& f : scan.faces) {
    const Eigen::Vector3d& a = scan.points[static_cast<std::size_t>(f[0])];
    const Eigen::Vector3d& b = scan.points[static_cast<std::size_t>(f[1])];
    const Eigen::Vector3d& c = scan.points[static_cast<std::size_t>(f[2])];
    const Eigen::Vector3d normal = (b - a).cross(c - a);  // length: twice the area
    const double area = normal.norm();
    total += area;
    facing += normal.dot(-(a + b + c)) > 0.0 ? area : 0.0;
  }
  if (!(total > 0.0)) {
    return hints;
  }
  hints.facing_share = facing / total;
  if (hints.facing_share < min_agreement && hints.facing_share > 1.0 - min_agreement) {
    return hints;  // not seen from the origin: another frame, or not a range image
  }
  hints.normals.reserve(scan.points.size());
  for (const auto& p : scan.points) {
    const double length = p.norm();
    hints.normals.push_back(length > 0.0 ? Eigen::Vector3d(-p / length) : Eigen::Vector3d::Zero());
  }
  return hints;
}

}  // namespace freeform_inspection
