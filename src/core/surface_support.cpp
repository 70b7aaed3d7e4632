// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/surface_support.h"

#include <algorithm>
#include <vector>

namespace freeform_inspection {

double surfaceOnCad(const SurfaceGraph& scan,
                    const Points& scan_points,
                    const MeshQuery& cad,
                    const Eigen::Isometry3d& T_cad_scan,
                    double band,
                    std::size_t count,
                    int min_links,
                    const CurvedSurface& curved) {
  const std::size_t cells = scan.size();
  if (cells == 0 || count == 0 || scan.point_cell.size() != scan_points.size()) {
    return 1.0;
  }
  // One real point per cell: the first that belongs to it.
  std::vector<int> point_of(cells, -1);
  for (std::size_t i = 0; i < scan.point_cell.size(); ++i) {
    const int c = scan.point_cell[i];
    if (c >= 0 && point_of[static_cast<std::size_t>(c)] < 0) {
      point_of[static_cast<std::size_t>(c)] = static_cast<int>(i);
    }
  }
  const std::size_t taken = std::min(cells, count);
  std::vector<char> surface(taken, 0);
  std::vector<char> on_cad(taken, 0);
  const auto n = static_cast<long>(taken);
#pragma omp parallel for schedule(static)
  for (long j = 0; j < n; ++j) {
    const auto u = static_cast<std::size_t>(j);
    const std::size_t cell = u * cells / taken;  // the verification set's spread
    const auto links = static_cast<int>(scan.offsets[cell + 1] - scan.offsets[cell]);
    if (links < min_links || point_of[cell] < 0) {
      continue;
    }
    surface[u] = 1;
    const Eigen::Vector3d p = T_cad_scan * scan_points[static_cast<std::size_t>(point_of[cell])];
    if (!curved.active()) {
      on_cad[u] = cad.closest(p, band).found ? 1 : 0;
      continue;
    }
    const ClosestPoint closest = cad.closest(p, band + curved.share * curved.chord->max);
    const double bulge =
        closest.found
            ? curved.share * bulgeAt(*curved.chord, cad.mesh(), closest.face, closest.point)
            : 0.0;
    on_cad[u] =
        closest.found && std::abs(closest.normal.dot(p - closest.point) - bulge) <= band ? 1 : 0;
  }
  const auto surface_cells = std::count(surface.begin(), surface.end(), 1);
  const auto supported = std::count(on_cad.begin(), on_cad.end(), 1);
  return surface_cells == 0 ? 1.0
                            : static_cast<double>(supported) / static_cast<double>(surface_cells);
}

}  // namespace freeform_inspection
