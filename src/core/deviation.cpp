// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/deviation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include <parallel/algorithm>

#include "freeform_inspection/deviation_colours.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/point_index.h"
#include "freeform_inspection/surface_graph.h"

namespace freeform_inspection {
namespace {

constexpr float kUnmatched = std::numeric_limits<float>::quiet_NaN();

double distanceToSegment(const Eigen::Vector3d& p,
                         const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// The scan runs past the edge of an open CAD surface when its closest point lies on a border
// edge and the offset leans more along the surface than across it: such a point has no
// nominal surface to deviate from.
bool pastBorder(const Model& model, const Eigen::Vector3d& point, const ClosestPoint& closest) {
  const auto& masks = model.faceBorderEdges();
  if (masks.empty() || masks[static_cast<std::size_t>(closest.face)] == 0) {
    return false;
  }
  const Eigen::Vector3d offset = point - closest.point;
  const double across = std::abs(offset.dot(closest.normal));
  const double along = (offset - offset.dot(closest.normal) * closest.normal).norm();
  if (along <= across) {
    return false;
  }
  const TriangleMesh& mesh = model.query().mesh();
  const Eigen::Vector3i& face = mesh.faces[static_cast<std::size_t>(closest.face)];
  const double on_edge = 1e-9 * model.bounds().diagonal();
  for (int e = 0; e < 3; ++e) {
    if ((masks[static_cast<std::size_t>(closest.face)] & (1U << e)) == 0) {
      continue;
    }
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(face[e])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(face[(e + 1) % 3])];
    if (distanceToSegment(closest.point, a, b) <= on_edge + 1e-12 * (b - a).norm()) {
      return true;
    }
  }
  return false;
}

// Value at fraction q of the sorted finite values (nearest rank).
double quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) {
    return 0.0;
  }
  const double rank = q * static_cast<double>(sorted.size() - 1);
  return sorted[static_cast<std::size_t>(std::lround(rank))];
}

std::vector<double> sortedFinite(const std::vector<float>& values) {
  std::vector<double> finite;
  finite.reserve(values.size());
  for (const float v : values) {
    if (std::isfinite(v)) {
      finite.push_back(v);
    }
  }
  // Values alone, so equal keys are equal values: the same array for any thread count.
  __gnu_parallel::sort(finite.begin(), finite.end());
  return finite;
}

}  // namespace

std::vector<std::string> validate(const ToleranceConfig& config) {
  std::vector<std::string> errors;
  if (!(config.upper > 0.0 && std::isfinite(config.upper))) {
    errors.push_back("tolerance.upper must be a finite length > 0 [m]");
  }
  if (!(config.lower < 0.0 && std::isfinite(config.lower))) {
    errors.push_back("tolerance.lower must be a finite length < 0 [m]");
  }
  return errors;
}

std::vector<std::string> validate(const DeviationConfig& config) {
  std::vector<std::string> errors;
  if (!(config.max_distance_ratio > 0.0 && config.max_distance_ratio <= 1.0)) {
    errors.push_back("deviation.max_distance_ratio must be in (0, 1]");
  }
  if (!(config.coverage_distance_cells > 0.0 && std::isfinite(config.coverage_distance_cells))) {
    errors.push_back("deviation.coverage_distance_cells must be a finite number > 0");
  }
  if (config.histogram_bins < 2 || config.histogram_bins > 1000) {
    errors.push_back("deviation.histogram_bins must be in [2, 1000]");
  }
  if (!(config.facing_tolerance_deg > 0.0 && config.facing_tolerance_deg <= 180.0)) {
    errors.push_back("deviation.facing_tolerance_deg must be in (0, 180]");
  }
  return errors;
}

SurfaceDistances measureDeviation(const Model& model,
                                  const Points& points_cad,
                                  double max_distance,
                                  const Points& normals_cad,
                                  double facing_deg) {
  std::vector<ClosestPoint> closest = model.query().closest(points_cad, max_distance);
  if (facing_deg < 180.0 && normals_cad.size() == points_cad.size()) {
    // Each point meets the closest surface facing its way, as ICP paired it: looked for again
    // only where the closest surface of all is turned away from it (the far side of a thin
    // wall, mostly), and kept when none facing its way lies within reach.
    constexpr double kDegree = 3.14159265358979323846 / 180.0;
    const double min_cos = std::cos(facing_deg * kDegree);
    Points turned_away;
    Points their_normals;
    std::vector<std::size_t> which;
    for (std::size_t i = 0; i < points_cad.size(); ++i) {
      if (closest[i].found && normals_cad[i].squaredNorm() > 0.0 &&
          closest[i].normal.dot(normals_cad[i]) < min_cos * normals_cad[i].norm()) {
        turned_away.push_back(points_cad[i]);
        their_normals.push_back(normals_cad[i]);
        which.push_back(i);
      }
    }
    // Normals that most of the scan turns away from its closest surface point into the
    // material (an inward winding): they tell nothing of which side a point is on.
    std::size_t found = 0;
    for (const ClosestPoint& c : closest) {
      found += c.found ? 1 : 0;
    }
    if (2 * which.size() > found) {
      turned_away.clear();
      their_normals.clear();
      which.clear();
    }
    const std::vector<ClosestPoint> facing =
        model.query().closestFacing(turned_away,
                                    their_normals,
                                    min_cos,
                                    true,
                                    max_distance,
                                    std::vector<int>(turned_away.size(), -1));
    for (std::size_t k = 0; k < which.size(); ++k) {
      if (facing[k].found) {
        closest[which[k]] = facing[k];
      }
    }
  }
  SurfaceDistances result;
  result.deviation.assign(points_cad.size(), kUnmatched);
  result.normals.assign(points_cad.size(), Eigen::Vector3d::Zero());
  result.faces.assign(points_cad.size(), -1);
  result.closest.assign(points_cad.size(), Eigen::Vector3d::Constant(kUnmatched));
  for (std::size_t i = 0; i < points_cad.size(); ++i) {
    if (!closest[i].found || pastBorder(model, points_cad[i], closest[i])) {
      continue;
    }
    result.deviation[i] = static_cast<float>(closest[i].signed_distance);
    result.normals[i] = closest[i].normal;
    result.faces[i] = closest[i].face;
    result.closest[i] = closest[i].point;
  }
  return result;
}

std::vector<float> shapeDeviation(const DescriptorResult& scan,
                                  const DescriptorResult& cad,
                                  const Eigen::Isometry3d& T_cad_scan,
                                  const Points& cad_normals) {
  std::vector<float> shape(cad_normals.size(), kUnmatched);
  const SurfaceGraph& cells = scan.graph;
  if (cells.size() == 0 || cad.graph.size() == 0 || cells.point_cell.size() != shape.size()) {
    return shape;
  }
  // Each scan cell is compared once with the CAD cell under it; its points share the value.
  // The CAD normal of a cell is the mean over its points, so the two sides of a thin wall
  // (opposite normals) are told apart.
  Points cell_normal(cells.size(), Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < shape.size(); ++i) {
    const int c = cells.point_cell[i];
    if (c >= 0) {
      cell_normal[static_cast<std::size_t>(c)] += cad_normals[i];
    }
  }
  const PointIndex cad_cells(cad.graph.centroids);
  const auto scales = static_cast<int>(std::min(scan.cell_values.cols(), cad.cell_values.cols()));
  std::vector<float> cell_shape(cells.size(), kUnmatched);
  const auto count = static_cast<long>(cells.size());
#pragma omp parallel for schedule(static)
  for (long c = 0; c < count; ++c) {
    const auto u = static_cast<std::size_t>(c);
    if (cell_normal[u].squaredNorm() == 0.0 || scales == 0) {
      continue;
    }
    const Eigen::Vector3d centre = T_cad_scan * cells.centroids[u];
    for (const Neighbour& n : cad_cells.nearest(centre, 4)) {
      if (cad.graph.normals[static_cast<std::size_t>(n.index)].dot(cell_normal[u]) <= 0.0) {
        continue;
      }
      double sum = 0.0;
      for (int k = 0; k < scales; ++k) {
        sum += std::abs(scan.cell_values(c, k) - cad.cell_values(n.index, k));
      }
      cell_shape[u] = static_cast<float>(sum / scales);
      break;
    }
  }
  for (std::size_t i = 0; i < shape.size(); ++i) {
    const int c = cells.point_cell[i];
    if (c >= 0 && std::isfinite(cad_normals[i].x()) && cad_normals[i].squaredNorm() > 0.0) {
      shape[i] = cell_shape[static_cast<std::size_t>(c)];
    }
  }
  return shape;
}

std::vector<bool> coveredCells(const Model& model, const Points& points_cad, double distance) {
  const SurfaceGraph& cells = model.descriptors().graph;
  std::vector<bool> covered(cells.size(), false);
  if (points_cad.empty() || cells.size() == 0) {
    return covered;
  }
  // One point per voxel of half the reach is as good as all of them for "is a point near", and
  // keeps a 1M-point scan's tree small.
  const std::vector<std::uint64_t> keys = voxelKeys(points_cad, 0.5 * distance);
  std::unordered_set<std::uint64_t> seen;
  Points kept;
  for (std::size_t i = 0; i < points_cad.size(); ++i) {
    if (seen.insert(keys[i]).second) {
      kept.push_back(points_cad[i]);
    }
  }
  const PointIndex scan(kept);
  // A scan sparser than the voxels (thinning kept most of it) still covers the surface between
  // its samples: reach 2.5 of its spacings.
  if (2 * kept.size() > points_cad.size()) {
    distance = std::max(distance, 2.5 * medianSpacing(kept, scan));
  }
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const auto nearest = scan.nearest(cells.centroids[c], 1);
    covered[c] = !nearest.empty() && nearest.front().squared_distance <= distance * distance;
  }
  return covered;
}

double coveredShare(const Model& model,
                    const std::vector<bool>& covered,
                    const std::vector<bool>& counted) {
  const SurfaceGraph& cells = model.descriptors().graph;
  double area = 0.0;
  double total = 0.0;
  for (std::size_t c = 0; c < cells.size() && c < covered.size(); ++c) {
    if (counted.empty() || counted[c]) {
      total += cells.area[c];
      area += covered[c] ? cells.area[c] : 0.0;
    }
  }
  return total > 0.0 ? area / total : 0.0;
}

double surfaceCoverage(const Model& model, const Points& points_cad, double distance) {
  return coveredShare(model, coveredCells(model, points_cad, distance));
}

double inToleranceFraction(const std::vector<float>& deviation, const ToleranceBands& tolerance) {
  std::size_t finite = 0;
  std::size_t inside = 0;
  for (std::size_t i = 0; i < deviation.size(); ++i) {
    if (std::isfinite(deviation[i])) {
      ++finite;
      inside += inTolerance(deviation[i], tolerance.at(i)) ? 1 : 0;
    }
  }
  return finite > 0 ? static_cast<double>(inside) / static_cast<double>(finite) : 0.0;
}

DeviationStatistics summarizeDeviation(const std::vector<float>& deviation,
                                       const ToleranceBands& tolerance,
                                       int histogram_bins) {
  DeviationStatistics stats;
  const std::vector<double> sorted = sortedFinite(deviation);
  stats.evaluated = sorted.size();
  stats.unmatched = deviation.size() - sorted.size();
  if (sorted.empty()) {
    return stats;
  }
  double sum = 0.0;
  double sum2 = 0.0;
  for (const double d : sorted) {
    sum += d;
    sum2 += d * d;
  }
  const auto n = static_cast<double>(sorted.size());
  stats.mean = sum / n;
  stats.rms = std::sqrt(sum2 / n);
  stats.std = std::sqrt(std::max(0.0, sum2 / n - stats.mean * stats.mean));
  stats.min = sorted.front();
  stats.max = sorted.back();
  stats.p5 = quantile(sorted, 0.05);
  stats.p50 = quantile(sorted, 0.50);
  stats.p95 = quantile(sorted, 0.95);
  stats.in_tolerance_fraction = inToleranceFraction(deviation, tolerance);
  // Symmetric bins wide enough for twice the band and the bulk of the data; the outer bins
  // take the tails so every point is counted.
  const double band = std::max(tolerance.part.upper, -tolerance.part.lower);
  const double reach =
      std::max({2.0 * band, std::abs(quantile(sorted, 0.005)), std::abs(quantile(sorted, 0.995))});
  const auto bins = static_cast<std::size_t>(histogram_bins);
  stats.histogram_counts.assign(bins, 0);
  for (std::size_t b = 0; b <= bins; ++b) {
    stats.histogram_edges.push_back(-reach + 2.0 * reach * static_cast<double>(b) /
                                                 static_cast<double>(bins));
  }
  for (const double d : sorted) {
    const double at = (d + reach) / (2.0 * reach) * static_cast<double>(bins);
    const auto bin = static_cast<std::size_t>(std::clamp(at, 0.0, static_cast<double>(bins - 1)));
    ++stats.histogram_counts[bin];
  }
  return stats;
}

void summarizeShapeDeviation(const std::vector<float>& shape, DeviationStatistics* stats) {
  const std::vector<double> sorted = sortedFinite(shape);
  double sum = 0.0;
  for (const double v : sorted) {
    sum += v;
  }
  stats->shape_mean = sorted.empty() ? 0.0 : sum / static_cast<double>(sorted.size());
  stats->shape_p95 = quantile(sorted, 0.95);
}

}  // namespace freeform_inspection
