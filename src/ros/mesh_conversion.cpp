// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <string>

#include "conversions.h"

namespace freeform_inspection_ros {

CloudConversion meshToScan(const pcl_msgs::PolygonMesh& mesh) {
  CloudConversion result = cloudToScan(mesh.cloud);
  if (!result.status.ok()) {
    return result;
  }
  result.scan.width = 0;  // the faces, not the grid, say which points are neighbours
  result.scan.height = 0;
  const std::size_t vertices = result.scan.points.size();
  std::size_t triangles = 0;
  for (const auto& polygon : mesh.polygons) {
    triangles += polygon.vertices.size() >= 3 ? polygon.vertices.size() - 2 : 0;
  }
  result.scan.faces.reserve(triangles);
  for (std::size_t p = 0; p < mesh.polygons.size(); ++p) {
    const auto& corners = mesh.polygons[p].vertices;
    std::string error;
    if (corners.size() < 3) {
      error = "polygon " + std::to_string(p) + " has " + std::to_string(corners.size()) +
              " vertices; at least 3 are needed";
    }
    for (const std::uint32_t corner : corners) {
      if (error.empty() && corner >= vertices) {
        error = "polygon " + std::to_string(p) + " refers to vertex " + std::to_string(corner) +
                " but the cloud has " + std::to_string(vertices);
      }
    }
    if (!error.empty()) {
      result.scan = fi::Scan{};
      result.status =
          fi::Status::failure(fi::StatusCode::kInvalidInput, "invalid PolygonMesh: " + error);
      return result;
    }
    // A fan keeps the polygon's winding, which orients the scan's normals.
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
      result.scan.faces.emplace_back(static_cast<int>(corners[0]),
                                     static_cast<int>(corners[k]),
                                     static_cast<int>(corners[k + 1]));
    }
  }
  return result;
}

}  // namespace freeform_inspection_ros
