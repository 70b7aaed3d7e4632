// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/surface_graph.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "cloud_neighbours_internal.h"

#include "freeform_inspection/mesh.h"

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
  const std::vector<std::uint64_t> keys =
      voxelKeys(s.cell_points != nullptr ? *s.cell_points : *s.points, cell_size);
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

// Neighbours of every cell, sorted and each once: bucketed by cell (counting sort), then each
// short bucket sorted on its own.
void linkCells(const std::vector<SurfaceEdge>& edges, SurfaceGraph* graph) {
  const std::size_t cells = graph->size();
  const auto cellOf = [&](int point) { return graph->point_cell[static_cast<std::size_t>(point)]; };
  std::vector<std::size_t> start(cells + 1, 0);
  for (const auto& [a, b] : edges) {
    const int ca = cellOf(a);
    const int cb = cellOf(b);
    if (ca >= 0 && cb >= 0 && ca != cb) {
      ++start[static_cast<std::size_t>(ca) + 1];
      ++start[static_cast<std::size_t>(cb) + 1];
    }
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> buckets(start.back());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (const auto& [a, b] : edges) {
    const int ca = cellOf(a);
    const int cb = cellOf(b);
    if (ca >= 0 && cb >= 0 && ca != cb) {
      buckets[fill[static_cast<std::size_t>(ca)]++] = cb;
      buckets[fill[static_cast<std::size_t>(cb)]++] = ca;
    }
  }
  // Each cell's bucket sorted and made unique in parallel, then copied out at its offset.
  graph->offsets.assign(cells + 1, 0);
  const auto signed_cells = static_cast<std::ptrdiff_t>(cells);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::ptrdiff_t c = 0; c < signed_cells; ++c) {
    const auto from = static_cast<std::size_t>(c);
    const auto first = buckets.begin() + static_cast<std::ptrdiff_t>(start[from]);
    const auto last = buckets.begin() + static_cast<std::ptrdiff_t>(start[from + 1]);
    std::sort(first, last);
    graph->offsets[from + 1] = static_cast<std::size_t>(std::unique(first, last) - first);
  }
  std::partial_sum(graph->offsets.begin(), graph->offsets.end(), graph->offsets.begin());
  graph->neighbours.resize(graph->offsets.back());
  graph->lengths.resize(graph->offsets.back());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::ptrdiff_t c = 0; c < signed_cells; ++c) {
    const auto from = static_cast<std::size_t>(c);
    for (std::size_t e = graph->offsets[from]; e < graph->offsets[from + 1]; ++e) {
      const int to = buckets[start[from] + (e - graph->offsets[from])];
      graph->neighbours[e] = to;
      graph->lengths[e] =
          (graph->centroids[from] - graph->centroids[static_cast<std::size_t>(to)]).norm();
    }
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

namespace internal {

// Each pair is kept by one of its two rows only (the lower index, unless it is not among the
// other's neighbours), so no sort is needed to remove duplicates; the acceptance test is
// symmetric, so either row decides the same. Counted, then filled at per-row offsets: the same
// list for any thread count.
std::vector<SurfaceEdge> cloudEdges(const Points& points,
                                    const Points& normals,
                                    const NeighbourTable& table,
                                    int neighbours,
                                    double max_length) {
  const int columns = std::min(neighbours + 1, table.k);
  const double max_squared = max_length * max_length;
  const auto accepted = [&](std::size_t i, int column) {
    const auto j = static_cast<std::size_t>(table.of(i)[column]);
    if (j == i || squaredDistance(points[i], points[j]) > max_squared) {
      return false;
    }
    const bool same_side = normals.empty() || normals[i].isZero() || normals[j].isZero() ||
                           normals[i].dot(normals[j]) > 0.0;
    if (!same_side) {
      return false;
    }
    const int* back = table.of(j);
    return j > i || std::find(back, back + columns, static_cast<int>(i)) == back + columns;
  };
  const std::size_t count = points.size();
  const auto signed_count = static_cast<std::ptrdiff_t>(count);
  const auto width = static_cast<std::size_t>(columns);
  std::vector<char> keep(count * width);
  std::vector<std::size_t> offsets(count + 1, 0);
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::ptrdiff_t p = 0; p < signed_count; ++p) {
    const auto i = static_cast<std::size_t>(p);
    for (int c = 0; c < columns; ++c) {
      const bool kept = accepted(i, c);
      keep[i * width + static_cast<std::size_t>(c)] = kept ? 1 : 0;
      offsets[i + 1] += kept ? 1 : 0;
    }
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  std::vector<SurfaceEdge> edges(offsets.back());
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::ptrdiff_t p = 0; p < signed_count; ++p) {
    const auto i = static_cast<std::size_t>(p);
    std::size_t next = offsets[i];
    for (std::size_t c = 0; c < width; ++c) {
      if (keep[i * width + c]) {
        const auto j = static_cast<std::size_t>(table.of(i)[c]);
        edges[next++] = {static_cast<int>(std::min(i, j)), static_cast<int>(std::max(i, j))};
      }
    }
  }
  return edges;
}

}  // namespace internal

std::vector<SurfaceEdge> cloudEdges(const Points& points,
                                    const Points& normals,
                                    int neighbours,
                                    double max_length) {
  std::vector<int> finite;
  Points kept;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].allFinite()) {
      finite.push_back(static_cast<int>(i));
      kept.push_back(points[i]);
    }
  }
  const Points kept_normals = normals.empty() ? Points() : [&] {
    Points selected;
    for (const int i : finite) {
      selected.push_back(normals[static_cast<std::size_t>(i)]);
    }
    return selected;
  }();
  const internal::NeighbourTable table = internal::nearestNeighbourTable(kept, neighbours + 1);
  std::vector<SurfaceEdge> edges =
      internal::cloudEdges(kept, kept_normals, table, neighbours, max_length);
  for (auto& [a, b] : edges) {  // back to the caller's indices (increasing, so still a < b)
    a = finite[static_cast<std::size_t>(a)];
    b = finite[static_cast<std::size_t>(b)];
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

}  // namespace freeform_inspection
