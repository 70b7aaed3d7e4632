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
#include <string>
#include <tuple>
#include <vector>

#include "cloud_neighbours_internal.h"
#include "cloud_visibility_internal.h"
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "freeform_inspection/curvature.h"

namespace freeform_inspection {
namespace {

constexpr int kMinNeighbours = 6;  // a stable PCA normal and shape-operator fit
constexpr double kPi = 3.14159265358979323846;
// Relative eigenvalue threshold of the shape-operator fit: below it the neighbours are (nearly)
// collinear or coincident, and the fitted curvature would be noise.
constexpr double kFitRankThreshold = 1e-6;

// The k nearest neighbours of every point (the first k columns of a shared table, nearest first
// and including the point itself).
struct Neighbourhoods {
  const internal::NeighbourTable* table = nullptr;
  int k = 0;

  const int* of(std::size_t point) const { return table->of(point); }
  std::size_t kth(std::size_t point) const { return std::size_t(of(point)[k - 1]); }
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

// Smallest eigenvector of the neighbourhood covariance (the direction the neighbours vary
// least) and the neighbourhood's mean, which the least-squares plane passes through.
struct PcaPlane {
  Eigen::Vector3d normal;
  Eigen::Vector3d mean;
};
PcaPlane pcaPlane(const Points& points, const int* neighbours, int k) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int j = 0; j < k; ++j) {
    mean += points[std::size_t(neighbours[j])];
  }
  mean /= double(k);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int j = 0; j < k; ++j) {  // the lower triangle, all the solver reads
    const Eigen::Vector3d d = points[std::size_t(neighbours[j])] - mean;
    for (int column = 0; column < 3; ++column) {
      for (int row = column; row < 3; ++row) {
        covariance(row, column) += d[row] * d[column];
      }
    }
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(covariance);  // closed form: the smallest eigenvalue is well separated
  return {solver.eigenvectors().col(0).normalized(), mean};
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
                      std::vector<char>& fixed,
                      Points& on_plane) {
  Points result(points.size());
  on_plane.resize(points.size());
  fixed.assign(points.size(), 0);
  const auto count = static_cast<std::ptrdiff_t>(points.size());
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const auto point = static_cast<std::size_t>(i);
    fixed[point] = hasGivenNormal(normals, point) ? 1 : 0;
    const PcaPlane plane = pcaPlane(points, hoods.of(point), hoods.k);
    result[point] = plane.normal;
    on_plane[point] = points[point] - plane.normal * plane.normal.dot(points[point] - plane.mean);
    if (fixed[point] && result[point].dot(normals[point]) < 0.0) {
      result[point] = -result[point];
    }
  }
  return result;
}

// Neighbours per point that the orientation tree may use. The tree needs a connected graph
// along the surface, not the curvature fit's 24: with 12 the normals agree with the CAD's as
// often as with 24 on the blade (99 % at 30k points, 99.7 % at 100k), at half the edges.
constexpr int kOrientationNeighbours = 12;

// Hoppe's weight (edges between nearly parallel normals first, so the orientation goes around
// sharp edges last) plus a penalty for stepping along the normals: the two sides of a thin wall
// (a blade's trailing edge) have parallel normals too, but the step between them is across the
// surface, not along it, and following it would flip a whole side. Symmetric: called with a < b.
double orientationWeight(const Points& points,
                         const Points& normals,
                         std::size_t a,
                         std::size_t b) {
  const Eigen::Vector3d step = (points[b] - points[a]).normalized();
  return 1.0 - std::abs(normals[a].dot(normals[b])) + std::abs(step.dot(normals[a])) +
         std::abs(step.dot(normals[b]));
}

// Whether the pair (point, column c of its row) is an edge this row owns: every pair is owned by
// exactly one of its two rows (the lower index when each is among the other's neighbours).
// Coincident points give no direction and are never joined.
bool ownsPair(const Neighbourhoods& hoods, const Points& points, std::size_t point, int column) {
  const auto other = std::size_t(hoods.of(point)[column]);
  if (other == point || points[other] == points[point]) {
    return false;
  }
  if (other > point) {
    return true;
  }
  const int* back = hoods.of(other);
  return std::find(back, back + hoods.k, static_cast<int>(point)) == back + hoods.k;
}

// An edge of the orientation graph, a < b. Sorting by (weight, a, b) is a strict total order,
// so the spanning tree does not depend on how the edges were produced or sorted.
struct WeightedEdge {
  double weight;
  std::uint32_t a;
  std::uint32_t b;

  bool operator<(const WeightedEdge& other) const {
    return std::tie(weight, a, b) < std::tie(other.weight, other.a, other.b);
  }
};

// Every pair of the orientation graph once, with its weight: counted per row, then filled at the
// row's offset (the same list for any thread count).
internal::LargeVector<WeightedEdge> orientationEdges(const Points& points,
                                                     const Points& normals,
                                                     const Neighbourhoods& hoods) {
  const std::size_t count = points.size();
  const auto signed_count = static_cast<std::ptrdiff_t>(count);
  const auto k = std::size_t(hoods.k);
  std::vector<char> owned(count * k);
  std::vector<std::size_t> offsets(count + 1, 0);
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::ptrdiff_t i = 0; i < signed_count; ++i) {
    const auto point = static_cast<std::size_t>(i);
    for (int c = 0; c < hoods.k; ++c) {
      const bool owns = ownsPair(hoods, points, point, c);
      owned[point * k + std::size_t(c)] = owns ? 1 : 0;
      offsets[point + 1] += owns ? 1 : 0;
    }
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  internal::LargeVector<WeightedEdge> edges(offsets.back());
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::ptrdiff_t i = 0; i < signed_count; ++i) {
    const auto point = static_cast<std::size_t>(i);
    std::size_t next = offsets[point];
    for (std::size_t c = 0; c < k; ++c) {
      if (owned[point * k + c]) {
        const auto other = std::size_t(hoods.of(point)[c]);
        const std::size_t a = std::min(point, other);
        const std::size_t b = std::max(point, other);
        edges[next++] = {orientationWeight(points, normals, a, b),
                         static_cast<std::uint32_t>(a),
                         static_cast<std::uint32_t>(b)};
      }
    }
  }
  return edges;
}

// Union-find with path halving; the root of a set is its smallest member.
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), 0u);
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  // False when a and b were already in one set.
  bool unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) {
      return false;
    }
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }

 private:
  std::vector<std::uint32_t> parent_;
};

// Ranges of the orientation graph at most this long are sorted whole.
constexpr std::ptrdiff_t kKruskalBaseCase = 2048;

// Filter-Kruskal (Osipov, Sanders and Singler 2009): the lighter half of the edges first, then
// the heavier half without the edges the lighter one already closed a cycle with. Most of a kNN
// graph's heavy edges are such, so they are never sorted. Under a strict total order the minimum
// spanning forest is unique, and the tree edges come out in Kruskal's order.
void filterKruskal(internal::LargeVector<WeightedEdge>::iterator first,
                   internal::LargeVector<WeightedEdge>::iterator last,
                   DisjointSets& sets,
                   internal::LargeVector<WeightedEdge>& tree) {
  if (last - first <= kKruskalBaseCase) {
    std::sort(first, last);
    for (auto edge = first; edge != last; ++edge) {
      if (sets.unite(edge->a, edge->b)) {
        tree.push_back(*edge);
      }
    }
    return;
  }
  const auto middle = first + (last - first) / 2;
  std::nth_element(first, middle, last);
  filterKruskal(first, middle, sets, tree);
  const auto open = std::remove_if(middle, last, [&sets](const WeightedEdge& edge) {
    return sets.find(edge.a) == sets.find(edge.b);
  });
  filterKruskal(middle, open, sets, tree);
}

// The minimum spanning forest of the orientation graph, with all the points that have a given
// normal joined beforehand (their orientation is known, so the tree only has to reach them, as
// a multi-source Prim would), as CSR adjacency.
struct Forest {
  std::vector<std::size_t> offsets;
  std::vector<std::uint32_t> targets;
};

Forest spanningForest(std::size_t count,
                      internal::LargeVector<WeightedEdge> edges,
                      const std::vector<int>& anchors) {
  DisjointSets sets(count);
  for (std::size_t i = 1; i < anchors.size(); ++i) {
    sets.unite(static_cast<std::uint32_t>(anchors[0]), static_cast<std::uint32_t>(anchors[i]));
  }
  internal::LargeVector<WeightedEdge> tree;
  tree.reserve(count);
  filterKruskal(edges.begin(), edges.end(), sets, tree);
  edges = {};
  Forest forest;
  forest.offsets.assign(count + 1, 0);
  for (const WeightedEdge& edge : tree) {
    ++forest.offsets[edge.a + 1];
    ++forest.offsets[edge.b + 1];
  }
  std::partial_sum(forest.offsets.begin(), forest.offsets.end(), forest.offsets.begin());
  forest.targets.resize(forest.offsets.back());
  std::vector<std::size_t> fill(forest.offsets.begin(), forest.offsets.end() - 1);
  for (const WeightedEdge& edge : tree) {
    forest.targets[fill[edge.a]++] = edge.b;
    forest.targets[fill[edge.b]++] = edge.a;
  }
  return forest;
}

// Walks the forest from the (already visited) seeds; each point reached is flipped to agree with
// the tree point it was reached from. Returns the points reached, seeds included.
std::vector<int> propagateOrientation(const std::vector<int>& seeds,
                                      const Forest& forest,
                                      Points& normals,
                                      std::vector<char>& visited) {
  std::vector<int> reached = seeds;
  for (std::size_t next = 0; next < reached.size(); ++next) {
    const auto from = std::size_t(reached[next]);
    for (std::size_t e = forest.offsets[from]; e < forest.offsets[from + 1]; ++e) {
      const std::size_t to = forest.targets[e];
      if (visited[to]) {
        continue;
      }
      visited[to] = 1;
      if (normals[from].dot(normals[to]) < 0.0) {
        normals[to] = -normals[to];
      }
      reached.push_back(static_cast<int>(to));
    }
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

// Visibility votes count only when this share of the points has one: a closed (full) scan gets
// most of its points voted (10-90 % on the benchmark parts), a single view almost none (at most
// 0.2 %), and those few, seen past a layer's edge, are as often wrong as right.
constexpr double kMinVotedShare = 0.05;

// Points whose normal's side the visibility from outside tells (their normals turned to it), or
// none when too few are told.
std::vector<int> visibleAnchors(const Points& points,
                                const Neighbourhoods& hoods,
                                double noise_sigma,
                                Points& normals) {
  internal::VisibilityConfig config;
  // Pixels twice the spacing (the distance to the 4th neighbour), so a surface covers its
  // pixels; a point is seen within a pixel and 3 σ of noise of the front-most.
  config.pixel = 2.0 * internal::tableDistance(points, *hoods.table, std::min(4, hoods.k - 1));
  config.depth_tolerance = config.pixel + 3.0 * noise_sigma;
  const std::vector<signed char> votes = internal::visibilityVotes(points, normals, config);
  std::vector<int> anchors;
  for (std::size_t i = 0; i < votes.size(); ++i) {
    if (votes[i] != 0) {
      anchors.push_back(static_cast<int>(i));
    }
  }
  if (double(anchors.size()) < kMinVotedShare * double(points.size())) {
    return {};
  }
  for (const int i : anchors) {
    if (votes[std::size_t(i)] < 0) {
      normals[std::size_t(i)] = -normals[std::size_t(i)];
    }
  }
  return anchors;
}

// Hoppe-style orientation along a minimum spanning tree of the kNN graph. Components holding
// given normals take their orientation from them; without given normals, points whose side the
// visibility from outside tells anchor the tree instead; the others, from the centroid vote.
// Nothing to do when every point has a given normal. Returns whether a share of the points
// worth matching (kMinVotedShare; not a few stray outliers) took its sign from the vote.
bool orientNormals(const Points& points,
                   const Neighbourhoods& hoods,
                   const std::vector<char>& fixed,
                   double noise_sigma,
                   Points& normals) {
  if (std::all_of(fixed.begin(), fixed.end(), [](char f) { return f != 0; })) {
    return false;
  }
  std::vector<int> anchors;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (fixed[i]) {
      anchors.push_back(static_cast<int>(i));
    }
  }
  if (anchors.empty()) {
    anchors = visibleAnchors(points, hoods, noise_sigma, normals);
  }
  const Neighbourhoods near{hoods.table, std::min(hoods.k, kOrientationNeighbours)};
  internal::LargeVector<WeightedEdge> edges = orientationEdges(points, normals, near);
  const Forest forest = spanningForest(points.size(), std::move(edges), anchors);
  std::vector<char> visited(points.size(), 0);
  for (const int i : anchors) {
    visited[std::size_t(i)] = 1;
  }
  propagateOrientation(anchors, forest, normals, visited);
  std::size_t guessed = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!visited[i]) {
      visited[i] = 1;
      const std::vector<int> component =
          propagateOrientation({static_cast<int>(i)}, forest, normals, visited);
      orientAwayFromCentroid(component, points, normals);
      guessed += component.size();
    }
  }
  return double(guessed) >= kMinVotedShare * double(points.size());
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

// Neighbours whose normal turned by more than this are on the other side of a thin wall.
constexpr double kOppositeSide = -0.5;

// Neighbours whose normal turned by more than 45° from the point's are left out of its quadric:
// the quadric is a height over the point's tangent plane, and there such a neighbour's surface
// climbs faster than the height can follow (slope above 1: a crease, a hole's wall, the far side
// of an edge) while its noise enters the height magnified by more than √2. Kept, they bent a
// machined block's faces near its bores and edges enough to slide a 2 %-noise view 2.5 % of L
// along its length (registration.md, "The quadric leaves out neighbours turned by more than 45°").
constexpr double kQuadricSide = 0.7071067811865476;  // cos 45°

// Relative pivot below which the quadric's six coefficients are not all determined (neighbours
// on a line, or too few across it), measured on coordinates scaled to unit tangent spread.
constexpr double kQuadricPivotRatio = 1e-4;

// The height over the point's tangent plane of the quadric fitted to its neighbours' heights.
Eigen::Vector3d ontoQuadric(
    const Points& points, const Points& normals, const int* neighbours, int k, std::size_t centre) {
  const Eigen::Vector3d& p = points[centre];
  const Eigen::Vector3d& normal = normals[centre];
  const Eigen::Matrix<double, 2, 3> basis = tangentBasis(normal);
  // Normal equations of the six coefficients, accumulated in one pass (lower triangle).
  using Vector6 = Eigen::Matrix<double, 6, 1>;
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  Matrix6 normal_matrix = Matrix6::Zero();
  Vector6 rhs = Vector6::Zero();
  for (int j = 0; j < k; ++j) {
    const auto other = std::size_t(neighbours[j]);
    if (normal.dot(normals[other]) < kQuadricSide) {
      continue;
    }
    const Eigen::Vector3d d = points[other] - p;
    const Eigen::Vector2d t = basis * d;
    Vector6 row;
    row << 1.0, t.x(), t.y(), t.x() * t.x(), t.x() * t.y(), t.y() * t.y();
    for (int column = 0; column < 6; ++column) {
      for (int r = column; r < 6; ++r) {
        normal_matrix(r, column) += row[r] * row[column];
      }
    }
    rhs += row * normal.dot(d);
  }
  const double used = normal_matrix(0, 0);
  const Eigen::Vector3d on_plane = p + normal * (rhs[0] / std::max(used, 1.0));
  const double spread = normal_matrix(3, 0) + normal_matrix(5, 0);  // Σ |t|²
  if (!(spread > 0.0)) {
    return on_plane;
  }
  // In units of the tangent spread, so the pivot test does not depend on the units.
  const double unit = 1.0 / std::sqrt(spread / used);
  Vector6 scale;
  scale << 1.0, unit, unit, unit * unit, unit * unit, unit * unit;
  const Matrix6 scaled = scale.asDiagonal() *
                         Matrix6(normal_matrix.selfadjointView<Eigen::Lower>()) *
                         scale.asDiagonal();
  const Eigen::LDLT<Matrix6> ldlt(scaled);
  const Vector6 pivots = ldlt.vectorD().cwiseAbs();
  if (ldlt.info() != Eigen::Success ||
      !(pivots.minCoeff() > kQuadricPivotRatio * pivots.maxCoeff())) {
    return on_plane;
  }
  const double height = ldlt.solve(scale.asDiagonal() * rhs)[0];  // constant term: unscaled
  return std::isfinite(height) ? Eigen::Vector3d(p + normal * height) : on_plane;
}

struct CurvatureFit {
  bool usable = false;
  double mean = 0.0;
};

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
    // The two equations of this neighbour, rows [t_x t_y 0] and [0 t_x t_y] over the unknowns
    // (a, b, c) of S = [a b; b c], added to the normal equations term by term (their zeros
    // skipped; the sums are the same).
    normal_matrix(0, 0) += t.x() * t.x();
    normal_matrix(0, 1) += t.x() * t.y();
    normal_matrix(1, 1) += t.y() * t.y() + t.x() * t.x();
    normal_matrix(1, 2) += t.x() * t.y();
    normal_matrix(2, 2) += t.y() * t.y();
    rhs(0) += t.x() * g.x();
    rhs(1) += t.y() * g.x() + t.x() * g.y();
    rhs(2) += t.y() * g.y();
  }
  normal_matrix(1, 0) = normal_matrix(0, 1);
  normal_matrix(2, 1) = normal_matrix(1, 2);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(normal_matrix, Eigen::EigenvaluesOnly);
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
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::ptrdiff_t i = 0; i < signed_count; ++i) {
    const auto point = static_cast<std::size_t>(i);
    const double kth = internal::squaredDistance(points[point], points[hoods.kth(point)]);
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

namespace internal {

Points ontoLocalQuadrics(const Points& points,
                         const Points& normals,
                         const NeighbourTable& table,
                         int k) {
  Points moved(points.size());
  const auto count = static_cast<std::ptrdiff_t>(points.size());
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const auto point = static_cast<std::size_t>(i);
    moved[point] = ontoQuadric(points, normals, table.of(point), k, point);
  }
  return moved;
}

CurvatureResult computeCloudCurvature(const Points& points,
                                      const Points& normals,
                                      const CloudCurvatureConfig& config,
                                      int table_k,
                                      NeighbourTable* table) {
  CurvatureResult result;
  result.status = checkInput(points, normals, config);
  if (!result.status.ok()) {
    return result;
  }
  if (table->k < config.neighbours) {
    *table = nearestNeighbourTable(points, std::max(table_k, config.neighbours));
  }
  const Neighbourhoods hoods{table, config.neighbours};
  std::vector<char> fixed;
  result.normals = initialNormals(points, normals, hoods, fixed, result.on_plane);
  result.signs_guessed = orientNormals(points, hoods, fixed, config.noise_sigma, result.normals);
  if (fitAllPoints(points, hoods, result) == 0) {
    result.status = Status::failure(StatusCode::kDegenerateInput,
                                    "cloud curvature: no point has a usable curvature fit (all " +
                                        std::to_string(points.size()) +
                                        " neighbourhoods coincident or collinear)");
  }
  return result;
}

}  // namespace internal

CurvatureResult computeCloudCurvature(const Points& points,
                                      const Points& normals,
                                      const CloudCurvatureConfig& config) {
  internal::NeighbourTable table;
  return internal::computeCloudCurvature(points, normals, config, config.neighbours, &table);
}

}  // namespace freeform_inspection
