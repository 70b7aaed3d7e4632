// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/descriptor.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>

#include "cloud_neighbours_internal.h"
#include <parallel/algorithm>

#include "freeform_inspection/geodesic.h"
#include "freeform_inspection/mesh_adjacency.h"
#include "freeform_inspection/point_index.h"

namespace freeform_inspection {
namespace {

// Neighbours of the cloud curvature fit. A fit over a neighbourhood no wider than a few σ of
// noise fits the noise: its normals turn at random and the curvature shrinks with them (a sphere
// at σ = 0.75 % of its diagonal read 0.77 of its H with 24 neighbours whose reach was just short
// of 3 σ). The configured k is raised until the neighbourhood's median radius reaches
// noise_fit_multiple · σ (the area grows with k), within max_cloud_neighbours and a table of at
// most kMaxTableEntries. It used to wait until that radius was 1.5× the configured one, which
// left 0.5 % noise on most parts in the shrinking range; see docs/descriptors.md.
int fitNeighbours(const Points& points,
                  const internal::NeighbourTable& table,
                  double noise_sigma,
                  const DescriptorConfig& config) {
  constexpr std::size_t kMaxTableEntries = 8000000;  // 32 MB of indices
  const int configured = config.cloud_curvature.neighbours;
  const double reach = internal::tableDistance(points, table, configured - 1);
  const double wanted = config.noise_fit_multiple * noise_sigma;
  if (!(reach > 0.0) || !(wanted > reach) || config.max_cloud_neighbours <= configured) {
    return configured;
  }
  const double grown = std::ceil(configured * (wanted / reach) * (wanted / reach));
  const auto table_limit =
      static_cast<double>(kMaxTableEntries / std::max<std::size_t>(points.size(), 1));
  const double limit = std::min({static_cast<double>(config.max_cloud_neighbours),
                                 table_limit,
                                 static_cast<double>(points.size())});
  return std::max(configured, static_cast<int>(std::min(grown, limit)));
}

// On clouds the k-nearest-neighbour table is computed once, wide enough for both the curvature
// fit and the surface edges, and handed back in `table` for cloudEdges.
CurvatureResult pointCurvature(const Points& points,
                               const Triangles& faces,
                               const Points& normals,
                               double noise_sigma,
                               const DescriptorConfig& config,
                               internal::NeighbourTable* table,
                               int* neighbours) {
  if (faces.empty()) {
    CloudCurvatureConfig fit = config.cloud_curvature;
    fit.noise_sigma = noise_sigma;
    const int table_k = std::max(fit.neighbours, config.cloud_edge_neighbours + 1);
    if (noise_sigma > 0.0 && points.size() >= static_cast<std::size_t>(table_k)) {
      *table = internal::nearestNeighbourTable(points, table_k);
      fit.neighbours = fitNeighbours(points, *table, noise_sigma, config);
    }
    *neighbours = fit.neighbours;
    return internal::computeCloudCurvature(
        points, normals, fit, std::max(table_k, fit.neighbours), table);
  }
  const MeshAdjacency adjacency = buildMeshAdjacency(faces, points.size());
  return computeMeshCurvature(points, faces, adjacency, config.mesh_curvature);
}

// eq. 6–7: H̃_k = Σ w_j a_j H_j / Σ w_j a_j over the ball of radius r_k, w_j = exp(−g_j / g_max),
// g_max the largest geodesic distance inside that ball. The paper's eq. 6 sums w_j·H_j
// unnormalised; we normalise (a weighted mean, so a plane gives exactly 0 whatever the sampling)
// and weight by the area each cell stands for (an integral, so uneven sampling does not bias).
// Summing a_j·H_j (the integrated curvature of each cell) also cancels the bias the paper's A/3
// vertex area gives eq. 3 at irregular vertices: Σ a_j H_j / Σ a_j is the total mean curvature
// of the ball over its area.
void averageOverBall(const SurfaceGraph& graph,
                     const std::vector<BallMember>& ball,
                     const std::vector<double>& radii,
                     Eigen::RowVectorXd* out) {
  std::size_t end = 0;
  for (std::size_t k = 0; k < radii.size(); ++k) {
    while (end < ball.size() && ball[end].distance <= radii[k]) {
      ++end;
    }
    const double g_max = ball[end - 1].distance;
    double weighted = 0.0;
    double weights = 0.0;
    for (std::size_t j = 0; j < end; ++j) {
      const auto cell = static_cast<std::size_t>(ball[j].cell);
      const double w = (g_max > 0.0 ? std::exp(-ball[j].distance / g_max) : 1.0) * graph.area[cell];
      weighted += w * graph.curvature[cell];
      weights += w;
    }
    (*out)[static_cast<Eigen::Index>(k)] = weighted / weights;
  }
}

Eigen::MatrixXd multiscaleCurvature(const SurfaceGraph& graph, const std::vector<double>& radii) {
  Eigen::MatrixXd curvature(static_cast<Eigen::Index>(graph.size()),
                            static_cast<Eigen::Index>(radii.size()));
#pragma omp parallel
  {
    GeodesicBallGrower grower(graph);  // scratch space per thread
    Eigen::RowVectorXd row(static_cast<Eigen::Index>(radii.size()));
#pragma omp for schedule(dynamic, 64)
    for (std::size_t c = 0; c < graph.size(); ++c) {
      const auto& ball = grower.grow(static_cast<int>(c), radii.back());
      averageOverBall(graph, ball, radii, &row);
      curvature.row(static_cast<Eigen::Index>(c)) = row;
    }
  }
  return curvature;
}

// Values of the coarse cells at the fine ones: an area- and distance-weighted mean over the
// coarse cell of the fine cell's first point and that cell's neighbours, so the field is smooth
// across the coarse cells' borders instead of stepping there.
Eigen::MatrixXd interpolateCells(const SurfaceGraph& coarse,
                                 const Eigen::MatrixXd& values,
                                 const SurfaceGraph& fine,
                                 double coarse_cell) {
  std::vector<int> fine_to_coarse(fine.size(), -1);
  for (std::size_t i = 0; i < fine.point_cell.size(); ++i) {
    const int f = fine.point_cell[i];
    if (f >= 0 && fine_to_coarse[static_cast<std::size_t>(f)] < 0) {
      fine_to_coarse[static_cast<std::size_t>(f)] = coarse.point_cell[i];
    }
  }
  const double inverse_spread = 2.0 / (coarse_cell * coarse_cell);
  Eigen::MatrixXd out(static_cast<Eigen::Index>(fine.size()), values.cols());
  for (std::size_t f = 0; f < fine.size(); ++f) {
    const auto g = static_cast<std::size_t>(fine_to_coarse[f]);
    Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(values.cols());
    double weights = 0.0;
    const auto add = [&](std::size_t c) {
      const double w =
          coarse.area[c] *
          std::exp(-inverse_spread * (coarse.centroids[c] - fine.centroids[f]).squaredNorm());
      sum += w * values.row(static_cast<Eigen::Index>(c));
      weights += w;
    };
    add(g);
    for (std::size_t e = coarse.offsets[g]; e < coarse.offsets[g + 1]; ++e) {
      add(static_cast<std::size_t>(coarse.neighbours[e]));
    }
    out.row(static_cast<Eigen::Index>(f)) = sum / weights;
  }
  return out;
}

// H̃_k of every fine cell, each scale averaged on its level's graph (scaleLevels).
Eigen::MatrixXd multilevelCurvature(const SurfaceSamples& samples,
                                    const std::vector<SurfaceEdge>& edges,
                                    const SurfaceGraph& fine,
                                    double cell,
                                    const std::vector<double>& radii,
                                    double ball_cells) {
  const std::vector<int> levels = scaleLevels(radii, cell, ball_cells);
  Eigen::MatrixXd curvature(static_cast<Eigen::Index>(fine.size()),
                            static_cast<Eigen::Index>(radii.size()));
  for (int level = 0; level <= levels.back(); ++level) {
    std::vector<double> level_radii;
    std::vector<Eigen::Index> columns;
    for (std::size_t k = 0; k < radii.size(); ++k) {
      if (levels[k] == level) {
        level_radii.push_back(radii[k]);
        columns.push_back(static_cast<Eigen::Index>(k));
      }
    }
    if (level_radii.empty()) {
      continue;
    }
    Eigen::MatrixXd values;
    if (level == 0) {
      values = multiscaleCurvature(fine, level_radii);
    } else {
      const double coarse_cell = cell * std::pow(2.0, level);
      const SurfaceGraph coarse = buildSurfaceGraph(samples, edges, coarse_cell);
      values =
          interpolateCells(coarse, multiscaleCurvature(coarse, level_radii), fine, coarse_cell);
    }
    for (std::size_t j = 0; j < columns.size(); ++j) {
      curvature.col(columns[j]) = values.col(static_cast<Eigen::Index>(j));
    }
  }
  return curvature;
}

// The points a cloud's curvature is computed on: the lowest-index point of every voxel (a real
// sample, never an average that could fall inside a thin wall). `representative` maps every
// point to its voxel's entry in the returned list.
std::vector<int> thinCloud(const Points& points, double voxel, std::vector<int>* representative) {
  std::vector<int> kept;
  representative->assign(points.size(), -1);
  const bool finite = std::all_of(
      points.begin(), points.end(), [](const Eigen::Vector3d& p) { return p.allFinite(); });
  if (!(voxel > 0.0) || !finite) {  // non-finite input is reported by the curvature stage
    std::iota(representative->begin(), representative->end(), 0);
    kept = *representative;
    return kept;
  }
  // (voxel, index) sorted: each voxel's run starts with its lowest-index point. Entries are
  // numbered in the order of those points, as a scan in index order would first meet them.
  const std::vector<std::uint64_t> keys = voxelKeys(points, voxel);
  std::vector<std::pair<std::uint64_t, int>> sorted(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    sorted[i] = {keys[i], static_cast<int>(i)};
  }
  __gnu_parallel::sort(sorted.begin(), sorted.end());  // unique pairs: any thread count agrees
  std::vector<int> first(points.size(), -1);           // per point: the lowest index of its voxel
  for (std::size_t j = 0; j < sorted.size(); ++j) {
    const bool starts = j == 0 || sorted[j].first != sorted[j - 1].first;
    first[static_cast<std::size_t>(sorted[j].second)] =
        starts ? sorted[j].second : first[static_cast<std::size_t>(sorted[j - 1].second)];
  }
  std::vector<int> entry(points.size(), -1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (first[i] == static_cast<int>(i)) {  // the voxel's representative
      entry[i] = static_cast<int>(kept.size());
      kept.push_back(static_cast<int>(i));
    }
    (*representative)[i] = entry[static_cast<std::size_t>(first[i])];
  }
  return kept;
}

// The entries of `values` at `indices` (empty when `values` is: optional normals).
template <typename T>
std::vector<T> select(const std::vector<T>& values, const std::vector<int>& indices) {
  std::vector<T> selected;
  if (values.empty()) {
    return selected;
  }
  selected.reserve(indices.size());
  for (const int i : indices) {
    selected.push_back(values[static_cast<std::size_t>(i)]);
  }
  return selected;
}

// Only the representatives marked in `keep` stay analysed; every other one joins its nearest
// kept one, and so do the points it stood for. One with no kept point within `max_join` stays
// analysed too: an outlier off the surface must not join a surface cell.
void keepAnalysed(const Points& points,
                  std::vector<char> keep,
                  double max_join,
                  std::vector<int>* analysed,
                  std::vector<int>* representative) {
  const std::size_t count = analysed->size();
  std::vector<std::size_t> chosen;  // entries of the kept ones, in order
  Points chosen_points;
  std::vector<std::size_t> others;
  Points other_points;
  for (std::size_t u = 0; u < count; ++u) {
    const Eigen::Vector3d& p = points[static_cast<std::size_t>((*analysed)[u])];
    (keep[u] != 0 ? chosen : others).push_back(u);
    (keep[u] != 0 ? chosen_points : other_points).push_back(p);
  }
  const std::vector<Neighbour> nearest = PointIndex(chosen_points).nearestEach(other_points);
  for (std::size_t o = 0; o < others.size(); ++o) {
    if (nearest[o].index < 0 || nearest[o].squared_distance > max_join * max_join) {
      keep[others[o]] = 1;  // nothing kept near it
    }
  }
  std::vector<int> slot(count, -1);  // old entry → new entry
  std::vector<int> kept;
  for (std::size_t u = 0; u < count; ++u) {
    if (keep[u] != 0) {
      slot[u] = static_cast<int>(kept.size());
      kept.push_back((*analysed)[u]);
    }
  }
  for (std::size_t o = 0; o < others.size(); ++o) {
    if (slot[others[o]] < 0) {
      slot[others[o]] = slot[chosen[static_cast<std::size_t>(nearest[o].index)]];
    }
  }
  for (int& r : *representative) {
    r = slot[static_cast<std::size_t>(r)];
  }
  *analysed = std::move(kept);
}

// At most `cap` of the voxel representatives are analysed: an evenly spread share of them.
// Coarser voxels would do the same faster, but a voxel wider than half a thin wall holds points
// of both sides, which then share one side's value (the blade's 0.6 mm trailing edge); the
// 0.1 r_1 voxels stay below that.
void capAnalysed(const Points& points,
                 std::size_t cap,
                 std::vector<int>* analysed,
                 std::vector<int>* representative) {
  const std::size_t count = analysed->size();
  if (cap == 0 || count <= cap) {
    return;
  }
  std::vector<char> keep(count, 0);
  for (std::size_t j = 0; j < cap; ++j) {
    keep[j * count / cap] = 1;  // deterministic, evenly spread
  }
  keepAnalysed(
      points, std::move(keep), std::numeric_limits<double>::infinity(), analysed, representative);
}

// A fixed pseudo-random number in [0, 1) per point index (splitmix64), so the share a noisy
// cloud keeps is the same whatever the thread count and spread without the pattern of a scan's
// index order (every third point of a row-major range image would keep every third column).
double indexHash(std::uint64_t index) {
  std::uint64_t z = index + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

// A noisy cloud's curvature fit must reach noise_fit_multiple · σ (fitNeighbours), and on a
// dense cloud that takes far more neighbours than a plane fit needs: 1 % noise on a 100k-point
// blade scan put ~700 points there (1,900 at 2 %), the fit was cut at the table's limit well
// short of 3 σ, and the scan took 2 s of descriptors and did not register. Detail finer than
// the noise is not measurable, so such a cloud is analysed on a random share of its points
// that puts about noise_fit_budget of them within that reach, and never fewer than 4 per cell
// area (the cells need points). The share comes from the median count within the reach
// around 256 evenly spread points.
void thinForNoise(const Points& points,
                  double noise_sigma,
                  double cell,
                  const DescriptorConfig& config,
                  std::vector<int>* analysed,
                  std::vector<int>* representative) {
  constexpr std::size_t kSamples = 256;
  constexpr double kPointsPerCell = 4.0;
  constexpr double kPi = 3.14159265358979323846;
  const double reach = config.noise_fit_multiple * noise_sigma;
  const std::size_t count = analysed->size();
  if (config.noise_fit_budget <= 0 || !(reach > 0.0) || !(cell > 0.0) ||
      count < 4 * static_cast<std::size_t>(config.noise_fit_budget)) {
    return;
  }
  const Points kept = select(points, *analysed);
  const PointIndex index(kept);
  const std::size_t samples = std::min(kSamples, count);
  std::vector<double> within(samples);
  for (std::size_t j = 0; j < samples; ++j) {
    within[j] = static_cast<double>(index.countWithin(kept[j * count / samples], reach));
  }
  std::nth_element(within.begin(), within.begin() + samples / 2, within.end());
  const double median = within[samples / 2];
  const double disk_cells = kPi * reach * reach / (cell * cell);
  const double wanted =
      std::max(static_cast<double>(config.noise_fit_budget), kPointsPerCell * disk_cells);
  if (!(median > 1.25 * wanted)) {
    return;  // already about as sparse as the fit needs
  }
  const double share = wanted / median;
  std::vector<char> keep(count, 0);
  for (std::size_t u = 0; u < count; ++u) {
    keep[u] = indexHash(static_cast<std::uint64_t>((*analysed)[u])) < share ? 1 : 0;
  }
  keepAnalysed(points, std::move(keep), reach, analysed, representative);
}

// Where the points of a noisy cloud fall into cells: each moved onto its neighbourhood's plane
// (the curvature fit grew to 3 σ, so the plane averages the noise out), unless that is more than
// 3 σ away (an outlier keeps its place). The raw points spread one surface over layers of cells
// about as thick as the noise: a partial view of the UR10e forearm at 0.5 % noise had 8,200
// cells against 4,000 noise-free, and each geodesic ball costs its cells. Only the cells change:
// their centroids are still means of the measured points (moving those too lost registrations,
// docs/descriptors.md).
Points pointsOnPlanes(const Points& points, const Points& on_plane, double noise_sigma) {
  if (on_plane.size() != points.size() || !(noise_sigma > 0.0)) {
    return {};
  }
  Points moved = points;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if ((on_plane[i] - points[i]).norm() <= 3.0 * noise_sigma) {
      moved[i] = on_plane[i];
    }
  }
  return moved;
}

Status checkRadii(const std::vector<double>& radii) {
  for (std::size_t k = 0; k < radii.size(); ++k) {
    if (!(radii[k] > 0.0) || !std::isfinite(radii[k]) || (k > 0 && radii[k] <= radii[k - 1])) {
      return Status::failure(StatusCode::kInvalidInput,
                             "kernel radii must be finite, positive and increasing");
    }
  }
  return radii.empty() ? Status::failure(StatusCode::kInvalidInput, "no kernel radius given")
                       : Status::success();
}

}  // namespace

std::vector<std::string> validate(const DescriptorConfig& config) {
  std::vector<std::string> errors;
  if (config.scales < 1) {
    errors.push_back("descriptor.scales must be at least 1");
  }
  if (!(config.max_radius_ratio > 0.0 && config.max_radius_ratio <= 1.0)) {
    errors.push_back("descriptor.max_radius_ratio must be in (0, 1]");
  }
  if (!(config.cell_ratio > 0.0 && config.cell_ratio <= 1.0)) {
    errors.push_back("descriptor.cell_ratio must be in (0, 1]");
  }
  if (!(config.coarse_ball_cells >= 0.0 && std::isfinite(config.coarse_ball_cells))) {
    errors.push_back("descriptor.coarse_ball_cells must be a finite value >= 0");
  }
  if (!(config.cloud_thinning_ratio >= 0.0 && config.cloud_thinning_ratio <= 1.0)) {
    errors.push_back("descriptor.cloud_thinning_ratio must be in [0, 1]");
  }
  if (!(config.cloud_edge_spacings >= 0.0 && std::isfinite(config.cloud_edge_spacings))) {
    errors.push_back("descriptor.cloud_edge_spacings must be a finite value >= 0");
  }
  if (config.cloud_edge_neighbours < 3) {
    errors.push_back("descriptor.cloud_edge_neighbours must be at least 3");
  }
  if (config.cloud_curvature.neighbours < 6) {
    errors.push_back("descriptor.cloud_neighbours must be at least 6 (a quadric has 6 terms)");
  }
  if (!(config.noise_fit_multiple >= 0.0 && std::isfinite(config.noise_fit_multiple))) {
    errors.push_back("descriptor.noise_fit_multiple must be a finite value >= 0");
  }
  if (config.max_cloud_neighbours < 6) {
    errors.push_back("descriptor.max_cloud_neighbours must be at least 6");
  }
  if (config.noise_fit_budget < 0) {
    errors.push_back("descriptor.noise_fit_budget must be >= 0");
  }
  return errors;
}

std::vector<double> kernelRadii(double cad_diagonal, const DescriptorConfig& config) {
  const double r_max = config.max_radius_ratio * cad_diagonal;
  std::vector<double> radii;
  for (int k = 1; k <= config.scales; ++k) {
    radii.push_back(k * r_max / config.scales);  // r_k = k · r_max / K (paper §3.3)
  }
  return radii;
}

// A ball many cells wide costs its area in cells from every cell, so the wide scales took most
// of the time on the finest graph; their values change only over distances of a coarser
// graph's cells.
std::vector<int> scaleLevels(const std::vector<double>& radii, double cell, double ball_cells) {
  std::vector<int> levels;
  for (const double r : radii) {
    int level = 0;
    while (ball_cells > 0.0 && r >= ball_cells * cell * std::pow(2.0, level + 1)) {
      ++level;
    }
    levels.push_back(level);
  }
  return levels;
}

double DescriptorResult::value(std::size_t point, int scale) const {
  const int cell = graph.point_cell[point];
  return cell < 0 ? std::numeric_limits<double>::quiet_NaN()
                  : cell_values(cell, static_cast<Eigen::Index>(scale));
}

bool DescriptorResult::fitGrew(const DescriptorConfig& config) const {
  return cloud_neighbours > config.cloud_curvature.neighbours && !curvature.on_plane.empty();
}

Points DescriptorResult::onFittedSurfaces(const Points& points) const {
  if (on_quadric.empty() || representative.empty()) {
    return on_quadric.size() == points.size() ? on_quadric : Points();
  }
  Points moved(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto r = static_cast<std::size_t>(representative[i]);
    if (analysed[r] == static_cast<int>(i)) {
      moved[i] = on_quadric[r];
    } else {  // the plane through on_quadric[r] with r's normal
      const Eigen::Vector3d& n = curvature.normals[r];
      moved[i] = points[i] - n * n.dot(points[i] - on_quadric[r]);
    }
  }
  return moved;
}

Points DescriptorResult::pointNormals(std::size_t count) const {
  if (representative.empty()) {
    return curvature.normals.size() == count ? curvature.normals : Points();
  }
  if (representative.size() != count) {
    return Points();
  }
  Points normals(count, Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < count; ++i) {
    const int r = representative[i];
    if (r >= 0 && static_cast<std::size_t>(r) < curvature.normals.size()) {
      normals[i] = curvature.normals[static_cast<std::size_t>(r)];
    }
  }
  return normals;
}

DescriptorResult computeDescriptors(const Points& points,
                                    const Triangles& faces,
                                    const Points& normals,
                                    const std::vector<double>& radii,
                                    const DescriptorConfig& config,
                                    double noise_sigma) {
  DescriptorResult result;
  result.radii = radii;
  result.status = checkRadii(radii);
  if (!result.status.ok()) {
    return result;
  }
  std::vector<int> representative;
  result.analysed =
      faces.empty()
          ? thinCloud(points, config.cloud_thinning_ratio * radii.front(), &representative)
          : std::vector<int>();
  if (faces.empty()) {
    capAnalysed(points, config.max_analysed_points, &result.analysed, &representative);
    thinForNoise(points,
                 noise_sigma,
                 config.cell_ratio * radii.front(),
                 config,
                 &result.analysed,
                 &representative);
  }
  const bool thinned = faces.empty() && result.analysed.size() < points.size();
  const Points analysed_points = thinned ? select(points, result.analysed) : Points();
  const Points& surface = thinned ? analysed_points : points;
  internal::NeighbourTable table;
  result.curvature = pointCurvature(surface,
                                    faces,
                                    thinned ? select(normals, result.analysed) : normals,
                                    noise_sigma,
                                    config,
                                    &table,
                                    &result.cloud_neighbours);
  result.status = result.curvature.status;
  if (!result.status.ok()) {
    return result;
  }
  // Edges up to r_1 join a scan sampled finer than the cells; a sparse one (3,000 points on the
  // blade: spacing ≈ r_1) would fall apart into islands no geodesic ball can grow over.
  const double edge_length =
      faces.empty()
          ? std::max(radii.front(),
                     config.cloud_edge_spacings * internal::tableDistance(surface, table, 1))
          : 0.0;
  const std::vector<SurfaceEdge> edges =
      faces.empty()
          ? internal::cloudEdges(
                surface, result.curvature.normals, table, config.cloud_edge_neighbours, edge_length)
          : meshEdges(faces);
  // A noisy cloud (meshes never are: their fit does not grow): cells from the planes, ICP's
  // points from the quadrics (registration.md, "Onto the neighbourhood quadrics").
  Points cell_points;
  if (result.fitGrew(config)) {
    cell_points = pointsOnPlanes(surface, result.curvature.on_plane, noise_sigma);
    result.on_quadric = internal::ontoLocalQuadrics(
        surface, result.curvature.normals, table, result.cloud_neighbours);
  }
  const SurfaceSamples samples{&surface,
                               &result.curvature.normals,
                               &result.curvature.area,
                               &result.curvature.mean,
                               cell_points.empty() ? nullptr : &cell_points};
  const double cell = config.cell_ratio * radii.front();
  result.graph = buildSurfaceGraph(samples, edges, cell);
  if (result.graph.size() > 0) {  // before the points of a thinned cloud are mapped back
    result.cell_curvature =
        multilevelCurvature(samples, edges, result.graph, cell, radii, config.coarse_ball_cells);
  }
  if (thinned) {  // every original point takes the cell of its voxel's representative
    std::vector<int> point_cell(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      point_cell[i] = result.graph.point_cell[static_cast<std::size_t>(representative[i])];
    }
    result.graph.point_cell = std::move(point_cell);
    result.representative = std::move(representative);
  }
  if (result.analysed.empty() || !thinned) {
    result.analysed.resize(points.size());
    std::iota(result.analysed.begin(), result.analysed.end(), 0);
  }
  if (result.graph.size() == 0) {
    result.status = Status::failure(StatusCode::kDegenerateInput, "surface has no area");
    return result;
  }
  result.cell_values.resizeLike(result.cell_curvature);
  for (Eigen::Index k = 0; k < result.cell_values.cols(); ++k) {
    // eq. 11: V_k = 1/2 − (3/16) · H̃_k · r_k
    result.cell_values.col(k) = (0.5 - 3.0 / 16.0 * radii[static_cast<std::size_t>(k)] *
                                           result.cell_curvature.col(k).array())
                                    .matrix();
  }
  return result;
}

}  // namespace freeform_inspection
