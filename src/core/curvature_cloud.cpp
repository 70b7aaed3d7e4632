// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// Mean curvature of an unorganized cloud: a quadric height field fitted to each point's k nearest
// neighbours, with normals from the scan or from PCA, oriented by propagation over the kNN graph.
// The Gaussian curvature stays empty for clouds (as curvature.h documents): the descriptor uses H
// only, and K from a per-point quadric is noisier still.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <queue>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "freeform_inspection/curvature.h"
#include "freeform_inspection/point_index.h"

namespace freeform_inspection {
namespace {

constexpr int kQuadricTerms = 6;
constexpr double kPi = 3.14159265358979323846;
// Relative pivot threshold of the quadric fit: below it the neighbours are (nearly) collinear,
// coincident or on a conic through too few points, and the fitted curvature would be noise.
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
  if (config.neighbours < kQuadricTerms) {
    return invalid("neighbours = " + std::to_string(config.neighbours) +
                   ", the quadric fit needs at least 6");
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

// Given normals (normalised) where usable, PCA normals elsewhere; `fixed` marks the given ones,
// whose orientation is trusted and never flipped.
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
    result[point] =
        fixed[point] ? normals[point].normalized() : pcaNormal(points, hoods.of(point), hoods.k);
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

// Hoppe's weight: edges between nearly parallel normals are trusted first, so the orientation
// goes around sharp edges last and by the most reliable route.
void pushEdges(int from,
               const Graph& graph,
               const Points& normals,
               const std::vector<char>& visited,
               EdgeQueue& queue) {
  const auto source = std::size_t(from);
  for (std::size_t e = graph.offsets[source]; e < graph.offsets[source + 1]; ++e) {
    const int to = graph.targets[e];
    if (!visited[std::size_t(to)]) {
      const double weight = 1.0 - std::abs(normals[source].dot(normals[std::size_t(to)]));
      queue.push({weight, to, from});
    }
  }
}

// Prim's minimum spanning tree grown from the (already visited) seeds; each point it reaches is
// flipped to agree with the tree point it was reached from. Returns the points reached.
std::vector<int> propagateOrientation(const std::vector<int>& seeds,
                                      const Graph& graph,
                                      Points& normals,
                                      std::vector<char>& visited) {
  EdgeQueue queue;
  for (const int seed : seeds) {
    pushEdges(seed, graph, normals, visited, queue);
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
    pushEdges(edge.to, graph, normals, visited, queue);
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
  propagateOrientation(anchors, graph, normals, visited);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!visited[i]) {
      visited[i] = 1;
      const std::vector<int> component =
          propagateOrientation({static_cast<int>(i)}, graph, normals, visited);
      orientAwayFromCentroid(component, points, normals);
    }
  }
}

// Any unit vector orthogonal to n; the quadric's gradient terms absorb the choice.
Eigen::Matrix3d localFrame(const Eigen::Vector3d& normal) {
  const Eigen::Vector3d helper =
      std::abs(normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d u = normal.cross(helper).normalized();
  Eigen::Matrix3d frame;
  frame.row(0) = u;
  frame.row(1) = normal.cross(u);
  frame.row(2) = normal;
  return frame;
}

// Mean curvature of h(u, v) = a u² + b uv + c v² + d u + e v + f at u = v = 0, signed so that a
// surface bending away from +h (a sphere seen from outside) is positive: minus the usual
// upward-normal formula for a graph.
double graphMeanCurvature(const Eigen::Matrix<double, kQuadricTerms, 1>& q) {
  const double a = q[0], b = q[1], c = q[2], d = q[3], e = q[4];
  const double gradient = 1.0 + d * d + e * e;
  const double upward = ((1.0 + e * e) * 2.0 * a - 2.0 * d * e * b + (1.0 + d * d) * 2.0 * c) /
                        (2.0 * std::pow(gradient, 1.5));
  return -upward;
}

struct QuadricFit {
  bool usable = false;
  double mean = 0.0;
};

// Least-squares quadric in the local frame, coordinates divided by `scale` (the neighbourhood
// radius) so the design matrix is well conditioned whatever the units; H scales back by 1/scale.
QuadricFit fitQuadric(const Points& points,
                      const int* neighbours,
                      int k,
                      const Eigen::Vector3d& centre,
                      const Eigen::Vector3d& normal,
                      double scale) {
  const Eigen::Matrix3d frame = localFrame(normal);
  Eigen::Matrix<double, Eigen::Dynamic, kQuadricTerms> design(k, kQuadricTerms);
  Eigen::VectorXd heights(k);
  for (int j = 0; j < k; ++j) {
    const Eigen::Vector3d local = frame * (points[std::size_t(neighbours[j])] - centre) / scale;
    const double u = local.x(), v = local.y();
    design.row(j) << u * u, u * v, v * v, u, v, 1.0;
    heights[j] = local.z();
  }
  Eigen::ColPivHouseholderQR<Eigen::Matrix<double, Eigen::Dynamic, kQuadricTerms>> qr(design);
  qr.setThreshold(kFitRankThreshold);
  if (qr.rank() < kQuadricTerms) {
    return {};
  }
  const Eigen::Matrix<double, kQuadricTerms, 1> coefficients = qr.solve(heights);
  const double mean = graphMeanCurvature(coefficients) / scale;
  return std::isfinite(mean) ? QuadricFit{true, mean} : QuadricFit{};
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
      const QuadricFit fit = fitQuadric(
          points, hoods.of(point), hoods.k, points[point], out.normals[point], std::sqrt(kth));
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
                                    "cloud curvature: no point has a usable quadric fit (all " +
                                        std::to_string(points.size()) +
                                        " neighbourhoods coincident or collinear)");
  }
  return result;
}

}  // namespace freeform_inspection
