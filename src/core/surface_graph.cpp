// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/surface_graph.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "freeform_inspection/mesh.h"
#include "freeform_inspection/point_index.h"

namespace freeform_inspection {
namespace {

// Union-find with path halving; roots are kept as the smallest index so cell numbering depends
// only on the input order (determinism across runs and thread counts).
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int find(int x) {
    while (parent_[static_cast<std::size_t>(x)] != x) {
      auto& p = parent_[static_cast<std::size_t>(x)];
      p = parent_[static_cast<std::size_t>(p)];
      x = p;
    }
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) {
      parent_[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  }

 private:
  std::vector<int> parent_;
};

bool usable(const SurfaceSamples& s, std::size_t i) {
  return (*s.area)[i] > 0.0 && std::isfinite((*s.area)[i]) && std::isfinite((*s.curvature)[i]);
}

// Cell of every usable point: connected (through `edges`) points of one voxel share a cell.
std::vector<int> assignCells(const SurfaceSamples& s,
                             const std::vector<SurfaceEdge>& edges,
                             double cell_size,
                             std::size_t* cell_count) {
  const std::size_t n = s.points->size();
  const std::vector<std::uint64_t> keys = voxelKeys(*s.points, cell_size);
  DisjointSets sets(n);
  for (const auto& [a, b] : edges) {
    const auto ua = static_cast<std::size_t>(a);
    const auto ub = static_cast<std::size_t>(b);
    if (keys[ua] == keys[ub] && usable(s, ua) && usable(s, ub)) {
      sets.unite(a, b);
    }
  }
  std::vector<int> root_cell(n, -1);
  std::vector<int> cell(n, -1);
  *cell_count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!usable(s, i)) {
      continue;
    }
    int& c = root_cell[static_cast<std::size_t>(sets.find(static_cast<int>(i)))];
    if (c < 0) {
      c = static_cast<int>((*cell_count)++);
    }
    cell[i] = c;
  }
  return cell;
}

void accumulateCells(const SurfaceSamples& s, SurfaceGraph* graph, std::size_t cells) {
  graph->centroids.assign(cells, Eigen::Vector3d::Zero());
  graph->normals.assign(cells, Eigen::Vector3d::Zero());
  graph->area.assign(cells, 0.0);
  graph->curvature.assign(cells, 0.0);
  for (std::size_t i = 0; i < graph->point_cell.size(); ++i) {
    const int c = graph->point_cell[i];
    if (c < 0) {
      continue;
    }
    const auto ci = static_cast<std::size_t>(c);
    const double a = (*s.area)[i];
    graph->area[ci] += a;
    graph->curvature[ci] += a * (*s.curvature)[i];
    graph->centroids[ci] += a * (*s.points)[i];
    graph->normals[ci] += a * (*s.normals)[i];
  }
  for (std::size_t c = 0; c < cells; ++c) {
    graph->curvature[c] /= graph->area[c];
    graph->centroids[c] /= graph->area[c];
    graph->normals[c] = graph->normals[c].normalized();
  }
}

void linkCells(const std::vector<SurfaceEdge>& edges, SurfaceGraph* graph) {
  std::vector<std::pair<int, int>> links;
  links.reserve(2 * edges.size());
  for (const auto& [a, b] : edges) {
    const int ca = graph->point_cell[static_cast<std::size_t>(a)];
    const int cb = graph->point_cell[static_cast<std::size_t>(b)];
    if (ca >= 0 && cb >= 0 && ca != cb) {
      links.emplace_back(ca, cb);
      links.emplace_back(cb, ca);
    }
  }
  std::sort(links.begin(), links.end());
  links.erase(std::unique(links.begin(), links.end()), links.end());
  graph->offsets.assign(graph->size() + 1, 0);
  for (const auto& link : links) {
    ++graph->offsets[static_cast<std::size_t>(link.first) + 1];
  }
  std::partial_sum(graph->offsets.begin(), graph->offsets.end(), graph->offsets.begin());
  for (const auto& [from, to] : links) {
    graph->neighbours.push_back(to);
    graph->lengths.push_back((graph->centroids[static_cast<std::size_t>(from)] -
                              graph->centroids[static_cast<std::size_t>(to)])
                                 .norm());
  }
}

}  // namespace

SurfaceGraph buildSurfaceGraph(const SurfaceSamples& samples,
                               const std::vector<SurfaceEdge>& edges,
                               double cell_size) {
  SurfaceGraph graph;
  std::size_t cells = 0;
  graph.point_cell = assignCells(samples, edges, cell_size, &cells);
  accumulateCells(samples, &graph, cells);
  linkCells(edges, &graph);
  return graph;
}

std::vector<std::uint64_t> voxelKeys(const Points& points, double cell_size) {
  const BoundingBox box = computeBoundingBox(points);
  const Eigen::Vector3d cells = (box.extent() / cell_size).array().floor() + 1.0;
  std::vector<std::uint64_t> keys(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d c = ((points[i] - box.min) / cell_size).array().floor();
    keys[i] = static_cast<std::uint64_t>(c.x() + cells.x() * (c.y() + cells.y() * c.z()));
  }
  return keys;
}

std::vector<SurfaceEdge> meshEdges(const Triangles& faces) {
  std::vector<SurfaceEdge> edges;
  edges.reserve(3 * faces.size());
  for (const auto& f : faces) {
    for (int i = 0; i < 3; ++i) {
      edges.emplace_back(std::min(f[i], f[(i + 1) % 3]), std::max(f[i], f[(i + 1) % 3]));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

std::vector<SurfaceEdge> cloudEdges(const Points& points,
                                    const Points& normals,
                                    int neighbours,
                                    double max_length) {
  const PointIndex index(points);
  std::vector<std::vector<SurfaceEdge>> per_point(points.size());
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (const Neighbour& nb : index.nearest(points[i], neighbours + 1)) {
      const auto j = static_cast<std::size_t>(nb.index);
      const bool same_side = normals.empty() || normals[i].isZero() || normals[j].isZero() ||
                             normals[i].dot(normals[j]) > 0.0;
      if (j != i && nb.squared_distance <= max_length * max_length && same_side) {
        per_point[i].emplace_back(static_cast<int>(std::min(i, j)),
                                  static_cast<int>(std::max(i, j)));
      }
    }
  }
  std::vector<SurfaceEdge> edges;
  for (const auto& list : per_point) {
    edges.insert(edges.end(), list.begin(), list.end());
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

}  // namespace freeform_inspection
