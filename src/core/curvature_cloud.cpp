// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// Mean curvature of an unorganized cloud: the shape operator fitted to the change of the normals
// towards each point's k nearest neighbours, with normals from the scan or from PCA, oriented by
// propagation over the kNN graph. The Gaussian curvature stays empty for clouds (as curvature.h
// documents): the descriptor uses H only.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <queue>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Eigenvalues>

#include "freeform_inspection/curvature.h"
#include "freeform_inspection/point_index.h"

namespace freeform_inspection {
namespace {

constexpr int kMinNeighbours = 6;  // a stable PCA normal and shape-operator fit
constexpr double kPi = 3.14159265358979323846;
// Relative eigenvalue threshold of the shape-operator fit: below it the neighbours are (nearly)
// collinear or coincident, and the fitted curvature would be noise.
constexpr double kFitRankThreshold = 1e-6;

// The k nearest neighbours of every point, row-major (point i's at [i·k, (i+1)·k)), nearest
// first and including the point itself, plus the squared distance to the k-th.
struct Neighbourhoods {
  int k = 0;
  std::vector<int> indices;
  std::vector<double> kth_squared_distance;

  const int* of(std::size_t point) const { return indices.data() + point * std::size_t(k); }
};

Status invalid(const std::string& message) {
  return Status::failure(StatusCode::kInvalidInput, "cloud curvature: " + message);
}

Status checkFinite(const Points& points, const char* what) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      return invalid(std::string(what) + " " + std::to_string(i) + " is not finite");
    }
  }
  return Status::success();
}

Status checkSizes(const Points& points, const Points& normals, const CloudCurvatureConfig& config) {
  if (points.empty()) {
    return invalid("the cloud is empty");
  }
  if (!normals.empty() && normals.size() != points.size()) {
    return invalid("normals.size() = " + std::to_string(normals.size()) +
                   " but points.size() = " + std::to_string(points.size()));
  }
  if (config.neighbours < kMinNeighbours) {
    return invalid("neighbours = " + std::to_string(config.neighbours) +
                   ", the curvature fit needs at least 6");
  }
  return Status::success();
}

// Invalid input first (sizes, then non-finite values), then too few points for one neighbourhood.
Status checkInput(const Points& points, const Points& normals, const CloudCurvatureConfig& config) {
  for (const Status& status : {checkSizes(points, normals, config),
                               checkFinite(points, "point"),
                               checkFinite(normals, "normal")}) {
    if (!status.ok()) {
      return status;
    }
  }
  if (points.size() < std::size_t(config.neighbours)) {
    return Status::failure(
        StatusCode::kDegenerateInput,
        "cloud curvature: " + std::to_string(points.size()) +
            " points, fewer than neighbours = " + std::to_string(config.neighbours));
  }
  return Status::success();
}

Neighbourhoods findNeighbourhoods(const Points& points, int k) {
  const PointIndex index(points);
  Neighbourhoods result;
  result.k = k;
  result.indices.resize(points.size() * std::size_t(k));
  result.kth_squared_distance.resize(points.size());
  const auto count = static_cast<std::ptrdiff_t>(points.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const auto point = static_cast<std::size_t>(i);
    const std::vector<Neighbour> found = index.nearest(points[point], k);
    for (std::size_t j = 0; j < found.size(); ++j) {
      result.indices[point * std::size_t(k) + j] = found[j].index;
    }
    result.kth_squared_distance[point] = found.back().squared_distance;
  }
  return result;
}

// Smallest eigenvector of the neighbourhood covariance: the direction the neighbours vary least.
Eigen::Vector3d pcaNormal(const Points& points, const int* neighbours, int k) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int j = 0; j < k; ++j) {
    mean += points[std::size_t(neighbours[j])];
  }
  mean /= double(k);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int j = 0; j < k; ++j) {
    const Eigen::Vector3d d = points[std::size_t(neighbours[j])] - mean;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  return solver.eigenvectors().col(0).normalized();
}

bool hasGivenNormal(const Points& normals, std::size_t point) {
  return !normals.empty() && normals[point].squaredNorm() > 0.0;
}

// PCA normals everywhere, turned to agree with the given normal where there is one; `fixed` marks
// those, whose orientation is trusted and never flipped. The given normals only orient: their
// directions come from the scanner's own estimator (or, in synthetic scans, from flat faces),
// and the curvature should depend on the measured points alone, like the CAD's.
Points initialNormals(const Points& points,
                      const Points& normals,
                      const Neighbourhoods& hoods,
                      std::vector<char>& fixed) {
  Points result(points.size());
  fixed.assign(points.size(), 0);
  const auto count = static_cast<std::ptrdiff_t>(points.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const auto point = static_cast<std::size_t>(i);
    fixed[point] = hasGivenNormal(normals, point) ? 1 : 0;
    result[point] = pcaNormal(points, hoods.of(point), hoods.k);
    if (fixed[point] && result[point].dot(normals[point]) < 0.0) {
      result[point] = -result[point];
    }
  }
  return result;
}

// The kNN graph made symmetric (CSR), so orientation can travel along an edge either way.
struct Graph {
  std::vector<std::size_t> offsets;
  std::vector<int> targets;
};

// Each kNN pair (i, j) gives edges i → j and j → i; duplicates are harmless to the tree.
template <class Visit>
void forEachKnnPair(const Neighbourhoods& hoods, std::size_t count, Visit visit) {
  for (std::size_t i = 0; i < count; ++i) {
    for (int j = 0; j < hoods.k; ++j) {
      visit(i, std::size_t(hoods.of(i)[j]));
    }
  }
}

Graph symmetricGraph(const Neighbourhoods& hoods, std::size_t count) {
  Graph graph;
  graph.offsets.assign(count + 1, 0);
  forEachKnnPair(hoods, count, [&](std::size_t i, std::size_t other) {
    ++graph.offsets[i + 1];
    ++graph.offsets[other + 1];
  });
  std::partial_sum(graph.offsets.begin(), graph.offsets.end(), graph.offsets.begin());
  graph.targets.resize(graph.offsets.back());
  std::vector<std::size_t> fill(graph.offsets.begin(), graph.offsets.end() - 1);
  forEachKnnPair(hoods, count, [&](std::size_t i, std::size_t other) {
    graph.targets[fill[i]++] = static_cast<int>(other);
    graph.targets[fill[other]++] = static_cast<int>(i);
  });
  return graph;
}

struct TreeEdge {
  double weight;
  int to;
  int from;
};

// Lightest edge first; ties by index so the tree (and so the result) is deterministic.
struct HeavierEdge {
  bool operator()(const TreeEdge& a, const TreeEdge& b) const {
    return std::tie(a.weight, a.to, a.from) > std::tie(b.weight, b.to, b.from);
  }
};

using EdgeQueue = std::priority_queue<TreeEdge, std::vector<TreeEdge>, HeavierEdge>;

// Hoppe's weight (edges between nearly parallel normals first, so the orientation goes around
// sharp edges last) plus a penalty for stepping along the normals: the two sides of a thin wall
// (a blade's trailing edge) have parallel normals too, but the step between them is across the
// surface, not along it, and following it would flip a whole side.
double orientationWeight(const Points& points,
                         const Points& normals,
                         std::size_t a,
                         std::size_t b) {
  const Eigen::Vector3d step = (points[b] - points[a]).normalized();
  return 1.0 - std::abs(normals[a].dot(normals[b])) + std::abs(step.dot(normals[a])) +
         std::abs(step.dot(normals[b]));
}

void pushEdges(int from,
               const Graph& graph,
               const Points& points,
               const Points& normals,
               const std::vector<char>& visited,
               EdgeQueue& queue) {
  const auto source = std::size_t(from);
  for (std::size_t e = graph.offsets[source]; e < graph.offsets[source + 1]; ++e) {
    const int to = graph.targets[e];
    if (!visited[std::size_t(to)] && points[source] != points[std::size_t(to)]) {
      queue.push({orientationWeight(points, normals, source, std::size_t(to)), to, from});
    }
  }
}

// Prim's minimum spanning tree grown from the (already visited) seeds; each point it reaches is
// flipped to agree with the tree point it was reached from. Returns the points reached.
std::vector<int> propagateOrientation(const std::vector<int>& seeds,
                                      const Graph& graph,
                                      const Points& points,
                                      Points& normals,
                                      std::vector<char>& visited) {
  EdgeQueue queue;
  for (const int seed : seeds) {
    pushEdges(seed, graph, points, normals, visited, queue);
  }
  std::vector<int> reached = seeds;
  while (!queue.empty()) {
    const TreeEdge edge = queue.top();
    queue.pop();
    const auto to = std::size_t(edge.to);
    if (visited[to]) {
      continue;
    }
    visited[to] = 1;
    if (normals[std::size_t(edge.from)].dot(normals[to]) < 0.0) {
      normals[to] = -normals[to];
    }
    reached.push_back(edge.to);
    pushEdges(edge.to, graph, points, normals, visited, queue);
  }
  return reached;
}

// Flips a component whose normals mostly point towards its centroid. Right for closed or
// mostly convex parts; for a nearly planar patch the vote is a coin toss (see descriptors.md).
void orientAwayFromCentroid(const std::vector<int>& component,
                            const Points& points,
                            Points& normals) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const int i : component) {
    centroid += points[std::size_t(i)];
  }
  centroid /= double(component.size());
  std::ptrdiff_t votes = 0;
  for (const int i : component) {
    const double side = normals[std::size_t(i)].dot(points[std::size_t(i)] - centroid);
    votes += side > 0.0 ? 1 : (side < 0.0 ? -1 : 0);
  }
  if (votes < 0) {
    for (const int i : component) {
      normals[std::size_t(i)] = -normals[std::size_t(i)];
    }
  }
}

// Components holding given normals take their orientation from them; the others, from the
// centroid vote.
void orientNormals(const Points& points,
                   const Neighbourhoods& hoods,
                   const std::vector<char>& fixed,
                   Points& normals) {
  const Graph graph = symmetricGraph(hoods, points.size());
  std::vector<char> visited(fixed);
  std::vector<int> anchors;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (fixed[i]) {
      anchors.push_back(static_cast<int>(i));
    }
  }
  propagateOrientation(anchors, graph, points, normals, visited);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!visited[i]) {
      visited[i] = 1;
      const std::vector<int> component =
          propagateOrientation({static_cast<int>(i)}, graph, points, normals, visited);
      orientAwayFromCentroid(component, points, normals);
    }
  }
}

// Tangent basis (two rows) of the plane orthogonal to n.
Eigen::Matrix<double, 2, 3> tangentBasis(const Eigen::Vector3d& normal) {
  const Eigen::Vector3d helper =
      std::abs(normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d u = normal.cross(helper).normalized();
  Eigen::Matrix<double, 2, 3> basis;
  basis.row(0) = u;
  basis.row(1) = normal.cross(u);
  return basis;
}

struct CurvatureFit {
  bool usable = false;
  double mean = 0.0;
};

// Neighbours whose normal turned by more than this are on the other side of a thin wall.
constexpr double kOppositeSide = -0.5;

// The shape operator S (symmetric 2×2 in the tangent plane) fitted by least squares to the
// normal changes towards the neighbours, n_j − n_i ≈ S·(p_j − p_i) in tangent coordinates;
// H = trace(S)/2. Unlike a height-field fit it follows the normals around edges sharper than
// the neighbourhood (a blade's leading and trailing edges), so the integrated curvature there
// is kept; and it is exact for a sphere (n = p/R gives S = I/R).
CurvatureFit fitShapeOperator(
    const Points& points, const Points& normals, const int* neighbours, int k, std::size_t centre) {
  const Eigen::Matrix<double, 2, 3> basis = tangentBasis(normals[centre]);
  Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (int j = 0; j < k; ++j) {
    const auto other = std::size_t(neighbours[j]);
    if (other == centre || normals[centre].dot(normals[other]) < kOppositeSide) {
      continue;
    }
    const Eigen::Vector2d t = basis * (points[other] - points[centre]);
    const Eigen::Vector2d g = basis * (normals[other] - normals[centre]);
    Eigen::Matrix<double, 2, 3> rows;  // unknowns (a, b, c) of S = [a b; b c]
    rows << t.x(), t.y(), 0.0, 0.0, t.x(), t.y();
    normal_matrix += rows.transpose() * rows;
    rhs += rows.transpose() * g;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(normal_matrix);
  const Eigen::Vector3d spread = eigen.eigenvalues();
  if (!(spread[2] > 0.0) || spread[0] < kFitRankThreshold * spread[2]) {
    return {};
  }
  const Eigen::Vector3d s = normal_matrix.ldlt().solve(rhs);
  const double mean = 0.5 * (s[0] + s[2]);
  return std::isfinite(mean) ? CurvatureFit{true, mean} : CurvatureFit{};
}

// H and area per point; returns how many points had a usable fit.
std::size_t fitAllPoints(const Points& points, const Neighbourhoods& hoods, CurvatureResult& out) {
  const std::size_t count = points.size();
  out.mean.assign(count, 0.0);
  out.area.assign(count, 0.0);
  std::vector<char> usable(count, 0);
  const auto signed_count = static_cast<std::ptrdiff_t>(count);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < signed_count; ++i) {
    const auto point = static_cast<std::size_t>(i);
    const double kth = hoods.kth_squared_distance[point];
    out.area[point] = kPi * kth / double(hoods.k);
    if (kth > 0.0) {
      const CurvatureFit fit =
          fitShapeOperator(points, out.normals, hoods.of(point), hoods.k, point);
      out.mean[point] = fit.mean;
      usable[point] = fit.usable ? 1 : 0;
    }
  }
  return std::size_t(std::count(usable.begin(), usable.end(), 1));
}

}  // namespace

CurvatureResult computeCloudCurvature(const Points& points,
                                      const Points& normals,
                                      const CloudCurvatureConfig& config) {
  CurvatureResult result;
  result.status = checkInput(points, normals, config);
  if (!result.status.ok()) {
    return result;
  }
  const Neighbourhoods hoods = findNeighbourhoods(points, config.neighbours);
  std::vector<char> fixed;
  result.normals = initialNormals(points, normals, hoods, fixed);
  orientNormals(points, hoods, fixed, result.normals);
  if (fitAllPoints(points, hoods, result) == 0) {
    result.status = Status::failure(StatusCode::kDegenerateInput,
                                    "cloud curvature: no point has a usable curvature fit (all " +
                                        std::to_string(points.size()) +
                                        " neighbourhoods coincident or collinear)");
  }
  return result;
}

}  // namespace freeform_inspection
