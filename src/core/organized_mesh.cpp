// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/organized_mesh.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

namespace freeform_inspection {
namespace {

// Row-major pixel grid over the caller's points; only built once the sizes are known to agree.
struct Grid {
  const Points& points;
  int width;
  int height;

  int at(int row, int column) const { return row * width + column; }
  bool finite(int index) const { return points[std::size_t(index)].allFinite(); }
  const Eigen::Vector3d& point(int index) const { return points[std::size_t(index)]; }
};

bool sizesAgree(const Points& points, int width, int height) {
  if (width < 2 || height < 2) {
    return false;
  }
  // Faces hold int indices, and the grid arithmetic is in int: refuse what would overflow.
  const auto cells = static_cast<std::int64_t>(width) * height;
  return cells == static_cast<std::int64_t>(points.size()) &&
         cells <= std::numeric_limits<int>::max();
}

void addEdgeLength(const Grid& grid, int a, int b, std::vector<double>& lengths) {
  if (grid.finite(a) && grid.finite(b)) {
    lengths.push_back((grid.point(a) - grid.point(b)).norm());
  }
}

std::vector<double> gridEdgeLengths(const Grid& grid) {
  std::vector<double> lengths;
  for (int row = 0; row < grid.height; ++row) {
    for (int column = 0; column < grid.width; ++column) {
      if (column + 1 < grid.width) {
        addEdgeLength(grid, grid.at(row, column), grid.at(row, column + 1), lengths);
      }
      if (row + 1 < grid.height) {
        addEdgeLength(grid, grid.at(row, column), grid.at(row + 1, column), lengths);
      }
    }
  }
  return lengths;
}

// Median length of the horizontal and vertical edges between finite pixels: the sampling step
// the occlusion threshold is measured against. Zero when there is no such edge.
double medianGridEdge(const Grid& grid) {
  std::vector<double> lengths = gridEdgeLengths(grid);
  if (lengths.empty()) {
    return 0.0;
  }
  const auto middle = lengths.begin() + std::ptrdiff_t(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  return *middle;
}

// Written as "not shorter" so that a NaN limit (a NaN ratio) drops the triangle too.
bool edgeTooLong(const Grid& grid, int a, int b, double limit) {
  return !((grid.point(a) - grid.point(b)).norm() <= limit);
}

void addTriangle(const Grid& grid, int a, int b, int c, double limit, Triangles& faces) {
  if (edgeTooLong(grid, a, b, limit) || edgeTooLong(grid, b, c, limit) ||
      edgeTooLong(grid, c, a, limit)) {
    return;
  }
  const Eigen::Vector3d normal =
      (grid.point(b) - grid.point(a)).cross(grid.point(c) - grid.point(a));
  if (normal.squaredNorm() > 0.0) {  // coincident or collinear corners have no orientation
    faces.emplace_back(a, b, c);
  }
}

// Corners of one grid cell: p<row offset><column offset>.
struct Cell {
  int p00, p01, p10, p11;
};

// Both triangles of a complete cell, split along the shorter diagonal (the flatter, more likely
// surface). All triangles are wound the same way in the image (p00 → p10 → p01 and its
// equivalents), so neighbouring faces traverse a shared edge in opposite directions.
void triangulateFullCell(const Grid& grid, const Cell& cell, double limit, Triangles& faces) {
  const double main_diagonal = (grid.point(cell.p00) - grid.point(cell.p11)).squaredNorm();
  const double anti_diagonal = (grid.point(cell.p01) - grid.point(cell.p10)).squaredNorm();
  if (main_diagonal <= anti_diagonal) {
    addTriangle(grid, cell.p00, cell.p10, cell.p11, limit, faces);
    addTriangle(grid, cell.p00, cell.p11, cell.p01, limit, faces);
  } else {
    addTriangle(grid, cell.p00, cell.p10, cell.p01, limit, faces);
    addTriangle(grid, cell.p01, cell.p10, cell.p11, limit, faces);
  }
}

// The one triangle that avoids the missing corner, in the same image winding.
void triangulateCellWithoutCorner(
    const Grid& grid, const Cell& cell, std::size_t missing, double limit, Triangles& faces) {
  const std::array<std::array<int, 3>, 4> without = {{{cell.p01, cell.p10, cell.p11},
                                                      {cell.p00, cell.p10, cell.p11},
                                                      {cell.p00, cell.p11, cell.p01},
                                                      {cell.p00, cell.p10, cell.p01}}};
  const auto& corners = without[missing];
  addTriangle(grid, corners[0], corners[1], corners[2], limit, faces);
}

void triangulateCell(const Grid& grid, int row, int column, double limit, Triangles& faces) {
  const Cell cell{grid.at(row, column),
                  grid.at(row, column + 1),
                  grid.at(row + 1, column),
                  grid.at(row + 1, column + 1)};
  const std::array<bool, 4> ok = {
      grid.finite(cell.p00), grid.finite(cell.p01), grid.finite(cell.p10), grid.finite(cell.p11)};
  const auto finite_count = std::count(ok.begin(), ok.end(), true);
  if (finite_count == 4) {
    triangulateFullCell(grid, cell, limit, faces);
  } else if (finite_count == 3) {
    const auto missing = std::size_t(std::find(ok.begin(), ok.end(), false) - ok.begin());
    triangulateCellWithoutCorner(grid, cell, missing, limit, faces);
  }
}

// Which way the image winding faces depends on how the scanner ordered rows and columns, so
// it is decided by a vote of the faces rather than assumed; one decision for all faces keeps the
// mesh consistently oriented even where a grazing, noisy face turns its back to the sensor.
void orientTowardsSensor(const Points& points, Triangles& faces) {
  std::int64_t votes = 0;
  for (const auto& face : faces) {
    const Eigen::Vector3d& a = points[std::size_t(face[0])];
    const Eigen::Vector3d normal =
        (points[std::size_t(face[1])] - a).cross(points[std::size_t(face[2])] - a);
    const Eigen::Vector3d centroid =
        (a + points[std::size_t(face[1])] + points[std::size_t(face[2])]) / 3.0;
    const double facing = -normal.dot(centroid);
    votes += facing > 0.0 ? 1 : (facing < 0.0 ? -1 : 0);
  }
  if (votes < 0) {
    for (auto& face : faces) {
      std::swap(face[1], face[2]);
    }
  }
}

}  // namespace

Triangles triangulateOrganizedGrid(const Points& points,
                                   int width,
                                   int height,
                                   const OrganizedMeshConfig& config) {
  Triangles faces;
  if (!sizesAgree(points, width, height)) {
    return faces;
  }
  const Grid grid{points, width, height};
  const double limit = config.max_edge_ratio * medianGridEdge(grid);
  for (int row = 0; row + 1 < height; ++row) {
    for (int column = 0; column + 1 < width; ++column) {
      triangulateCell(grid, row, column, limit, faces);
    }
  }
  orientTowardsSensor(points, faces);
  return faces;
}

}  // namespace freeform_inspection
