// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/support_plane.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <unordered_map>
#include <utility>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "freeform_inspection/point_index.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;
// RANSAC runs on an even subsample: a support worth removing holds a good share of the scan, so
// a few thousand points find it, and 200 draws find a plane holding 20 % of them with
// probability 1 − (1 − 0.2³)^200 = 0.8 (0.996 at 30 %).
constexpr std::size_t kRansacPoints = 2000;
constexpr int kRansacIterations = 200;
constexpr std::uint64_t kRansacSeed = 20261205;
// The grid that joins a plane's points into patches: cells at least this share of L wide, and
// at least this many point spacings (1 / √density), so the sparser far side of a table and its
// dropouts stay joined.
constexpr double kMinGridRatio = 0.02;
constexpr double kGridSpacings = 3.0;
// The surface density is measured from each of this many points' distance to its k-th nearest
// neighbour.
constexpr std::size_t kDensitySamples = 500;
constexpr int kDensityNeighbours = 8;
// A plane's patches are measured on an even sample of at most this many of its points (its
// density read from the same sample): enough for cells of a few per cent of L.
constexpr std::size_t kMaxPatchPoints = 20000;
// A cell is surface when it holds this share of the points the surface puts in it, and at least
// this many.
constexpr double kMinCellShare = 0.5;
constexpr double kMinCellPoints = 3.0;
// A patch is wider than the part when it exceeds L by this share and two grid cells (the
// width is measured on cell centres).
constexpr double kWidthMargin = 0.05;
// The widths of a patch are taken along this many directions in the plane.
constexpr int kWidthDirections = 16;
// Noise floor of the band, as a share of L (the pipeline's floor of a residual).
constexpr double kMinNoiseRatio = 1e-3;
// The band's half-width at most, as a share of the part's thickness: a band half as thick as
// the part holds no more than a slice of it.
constexpr double kMaxBandOfThickness = 0.25;

// At most `count` of the indices, evenly spread over the list (deterministic).
std::vector<int> evenSample(const std::vector<int>& indices, std::size_t count) {
  std::vector<int> sample;
  const std::size_t n = indices.size();
  const std::size_t taken = std::min(n, count);
  sample.reserve(taken);
  for (std::size_t i = 0; i < taken; ++i) {
    sample.push_back(indices[i * n / taken]);
  }
  return sample;
}

// The plane through the inliers of `candidate` among `sample` (within `band`), refitted to
// them by least squares (the covariance's least eigenvector), and how many they are.
std::pair<Eigen::Vector4d, std::size_t> refitted(const Points& points,
                                                 const std::vector<int>& sample,
                                                 const Eigen::Vector4d& candidate,
                                                 double band) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::vector<const Eigen::Vector3d*> inliers;
  for (const int i : sample) {
    const Eigen::Vector3d& p = points[static_cast<std::size_t>(i)];
    if (std::abs(candidate.head<3>().dot(p) + candidate[3]) <= band) {
      inliers.push_back(&p);
      mean += p;
    }
  }
  if (inliers.size() < 3) {
    return {candidate, inliers.size()};
  }
  mean /= static_cast<double>(inliers.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d* p : inliers) {
    covariance += (*p - mean) * (*p - mean).transpose();
  }
  const Eigen::Vector3d normal =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(0);
  Eigen::Vector4d plane;
  plane << normal, -normal.dot(mean);
  return {plane, inliers.size()};
}

// The dominant plane of the points `sample` (n·x + d = 0, n unit): RANSAC over planes through
// three of them, the one with the most points within `band` refitted to those points; zero when
// no three points span a plane. A fixed seed makes it reproducible. (PCL's RANSAC does the same,
// but logs an error line for every degenerate draw, on every scan, with only a process-wide
// switch to silence it.)
Eigen::Vector4d dominantPlane(const Points& points, const std::vector<int>& sample, double band) {
  if (sample.size() < 3) {
    return Eigen::Vector4d::Zero();
  }
  std::mt19937_64 rng(kRansacSeed);
  // The raw output, so every standard library draws the same points.
  const auto pick = [&rng, &sample] { return sample[rng() % sample.size()]; };
  Eigen::Vector4d best = Eigen::Vector4d::Zero();
  std::size_t best_count = 0;
  for (int draw = 0; draw < kRansacIterations; ++draw) {
    const Eigen::Vector3d& a = points[static_cast<std::size_t>(pick())];
    const Eigen::Vector3d& b = points[static_cast<std::size_t>(pick())];
    const Eigen::Vector3d& c = points[static_cast<std::size_t>(pick())];
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    const double length = normal.norm();
    if (!(length > 0.0)) {
      continue;  // coincident or collinear points span no plane
    }
    const Eigen::Vector3d unit = normal / length;
    const double offset = -unit.dot(a);
    std::size_t count = 0;
    for (const int i : sample) {
      count += std::abs(unit.dot(points[static_cast<std::size_t>(i)]) + offset) <= band ? 1 : 0;
    }
    if (count > best_count) {
      best_count = count;
      best << unit, offset;
    }
  }
  if (best_count < 3) {
    return Eigen::Vector4d::Zero();
  }
  return refitted(points, sample, best, band).first;
}

// Points per unit area of the surface the points sample: the median over an even sample of
// k / (π d_k²), d_k the distance to the k-th nearest other point. (The nearest neighbour alone
// reads a random sampling as ~4.5 times denser than it is.)
double surfaceDensity(const Points& points) {
  if (points.size() <= static_cast<std::size_t>(kDensityNeighbours)) {
    return 0.0;
  }
  const PointIndex index(points);
  std::vector<double> densities;
  const std::size_t taken = std::min(points.size(), kDensitySamples);
  for (std::size_t s = 0; s < taken; ++s) {
    const Eigen::Vector3d& p = points[s * points.size() / taken];
    const std::vector<Neighbour> near = index.nearest(p, kDensityNeighbours + 1);  // with itself
    const double squared = near.back().squared_distance;
    if (squared > 0.0) {
      densities.push_back(kDensityNeighbours / (kPi * squared));
    }
  }
  if (densities.empty()) {
    return 0.0;
  }
  const auto middle = densities.begin() + static_cast<std::ptrdiff_t>(densities.size() / 2);
  std::nth_element(densities.begin(), middle, densities.end());
  return *middle;
}

// The extents of a set of points of the plane along kWidthDirections directions; its width is
// the largest (within cos(π / 32) of the true diameter).
class Widths {
 public:
  Widths() {
    for (int d = 0; d < kWidthDirections; ++d) {
      const double angle = kPi * d / kWidthDirections;
      directions_[static_cast<std::size_t>(d)] = {std::cos(angle), std::sin(angle)};
    }
    low_.fill(std::numeric_limits<double>::infinity());
    high_.fill(-std::numeric_limits<double>::infinity());
  }
  void add(double x, double y) {
    for (std::size_t d = 0; d < directions_.size(); ++d) {
      const double along = x * directions_[d].first + y * directions_[d].second;
      low_[d] = std::min(low_[d], along);
      high_[d] = std::max(high_[d], along);
    }
  }
  double width() const {
    double widest = 0.0;
    for (std::size_t d = 0; d < directions_.size(); ++d) {
      widest = std::max(widest, high_[d] - low_[d]);
    }
    return widest;
  }

 private:
  std::array<std::pair<double, double>, kWidthDirections> directions_;
  std::array<double, kWidthDirections> low_;
  std::array<double, kWidthDirections> high_;
};

// Width of the widest connected patch of `members` on a grid in the plane, and the grid's cell.
struct PatchWidth {
  double width = 0.0;  // [m]
  double cell = 0.0;   // [m]
};

PatchWidth widestPatch(const Points& points,
                       const std::vector<int>& members,
                       const Eigen::Vector3d& normal,
                       double part_diameter) {
  Points on_plane;
  for (const int i : evenSample(members, kMaxPatchPoints)) {
    on_plane.push_back(points[static_cast<std::size_t>(i)]);
  }
  const double density = surfaceDensity(on_plane);
  PatchWidth result;
  result.cell = std::max(kMinGridRatio * part_diameter,
                         density > 0.0 ? kGridSpacings / std::sqrt(density) : 0.0);
  // A cell with less than half the points the surface puts in one (or fewer than 3) holds stray
  // points, not surface: outliers that happen to lie in the band must not join into a patch
  // (20 % outliers in the box of a thin blade put ~1 in every cell of a band through it, and
  // chained them wider than the part before this rule).
  const double min_count =
      std::max(kMinCellPoints, kMinCellShare * density * result.cell * result.cell);
  const Eigen::Vector3d u = normal.unitOrthogonal();  // two axes in the plane
  const Eigen::Vector3d v = normal.cross(u);
  using Cell = std::pair<std::int64_t, std::int64_t>;
  const auto key = [](const Cell& c) {
    return (static_cast<std::uint64_t>(c.first) << 32) ^
           static_cast<std::uint64_t>(c.second & 0xffffffff);
  };
  std::unordered_map<std::uint64_t, std::pair<Cell, double>> counted;
  for (const Eigen::Vector3d& p : on_plane) {
    const Cell c{static_cast<std::int64_t>(std::floor(p.dot(u) / result.cell)),
                 static_cast<std::int64_t>(std::floor(p.dot(v) / result.cell))};
    counted.emplace(key(c), std::make_pair(c, 0.0)).first->second.second += 1.0;
  }
  std::unordered_map<std::uint64_t, Cell> cells;
  for (const auto& [cell_key, cell] : counted) {
    if (cell.second >= min_count) {
      cells.emplace(cell_key, cell.first);
    }
  }
  // Patches: cells joined to their eight neighbours.
  std::unordered_map<std::uint64_t, char> seen;
  std::vector<Cell> stack;
  for (const auto& [start_key, start] : cells) {
    if (!seen.emplace(start_key, 1).second) {
      continue;
    }
    Widths patch;
    stack.assign(1, start);
    while (!stack.empty()) {
      const Cell c = stack.back();
      stack.pop_back();
      patch.add(static_cast<double>(c.first) + 0.5, static_cast<double>(c.second) + 0.5);
      for (std::int64_t da = -1; da <= 1; ++da) {
        for (std::int64_t db = -1; db <= 1; ++db) {
          const Cell next{c.first + da, c.second + db};
          if (cells.count(key(next)) != 0 && seen.emplace(key(next), 1).second) {
            stack.push_back(next);
          }
        }
      }
    }
    result.width = std::max(result.width, patch.width() * result.cell);
  }
  return result;
}

// The width of all of `members` in the plane, connected or not: no patch of them is wider.
double extentInPlane(const Points& points,
                     const std::vector<int>& members,
                     const Eigen::Vector3d& normal) {
  const Eigen::Vector3d u = normal.unitOrthogonal();
  const Eigen::Vector3d v = normal.cross(u);
  Widths all;
  for (const int i : members) {
    const Eigen::Vector3d& p = points[static_cast<std::size_t>(i)];
    all.add(p.dot(u), p.dot(v));
  }
  return all.width();
}

}  // namespace

std::vector<std::string> validate(const SupportConfig& config) {
  std::vector<std::string> errors;
  if (config.max_planes < 0) {
    errors.push_back("support.max_planes must be at least 0");
  }
  if (!(config.min_share > 0.0 && config.min_share <= 1.0)) {
    errors.push_back("support.min_share must be in (0, 1]");
  }
  if (!(config.band_sigmas > 0.0 && std::isfinite(config.band_sigmas))) {
    errors.push_back("support.band_sigmas must be a finite value > 0");
  }
  return errors;
}

std::vector<std::string> SupportResult::describe() const {
  std::vector<std::string> lines;
  for (const SupportPlane& plane : planes) {
    char text[200];
    std::snprintf(text,
                  sizeof(text),
                  "removed a support plane wider than the part (a table or fixture plate): %zu "
                  "points, %.3g m wide, normal (%.3f, %.3f, %.3f) in the scan frame",
                  plane.points,
                  plane.width,
                  plane.plane[0],
                  plane.plane[1],
                  plane.plane[2]);
    lines.emplace_back(text);
  }
  return lines;
}

SupportResult findSupports(const Points& points,
                           double noise_sigma,
                           double part_diameter,
                           double part_thickness,
                           const SupportConfig& config) {
  SupportResult result;
  result.on_support.assign(points.size(), 0);
  if (!config.remove || config.max_planes == 0 || points.size() < 3 || !(part_diameter > 0.0)) {
    return result;
  }
  // The band holds the support's noise and must not hold the part: a noise estimate that stray
  // points inflate (20 % outliers about a 10 mm bar: 1.30-1.36 % of L for 0.5 %) made a band
  // of ±5.3 mm, the whole bar lay in it, and with the strays it was "wider than the part".
  const double band =
      std::min(config.band_sigmas * std::max(noise_sigma, kMinNoiseRatio * part_diameter),
               kMaxBandOfThickness * part_thickness);
  const auto enough =
      static_cast<std::size_t>(std::ceil(config.min_share * static_cast<double>(points.size())));
  std::vector<int> remaining(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    remaining[i] = static_cast<int>(i);
  }
  // A plane that is not a support (a face of the part) leaves the search too, so a support that
  // holds fewer points than the part's largest face is still found; two more planes than
  // supports are tried.
  for (int attempt = 0; attempt < config.max_planes + 2 &&
                        static_cast<int>(result.planes.size()) < config.max_planes &&
                        remaining.size() >= std::max<std::size_t>(enough, 3);
       ++attempt) {
    const Eigen::Vector4d plane = dominantPlane(points, evenSample(remaining, kRansacPoints), band);
    if (plane.isZero()) {
      break;
    }
    std::vector<int> members;
    std::vector<int> rest;
    for (const int i : remaining) {
      const Eigen::Vector3d& p = points[static_cast<std::size_t>(i)];
      (std::abs(plane.head<3>().dot(p) + plane[3]) <= band ? members : rest).push_back(i);
    }
    if (members.size() < enough) {
      break;  // the largest plane left is too small to matter
    }
    // Wider than the part: a support. (The plain extent first: a face of a part without stray
    // points is never wider, and it is measured without the grid.)
    const double wider = (1.0 + kWidthMargin) * part_diameter;
    PatchWidth patch;
    if (extentInPlane(points, members, plane.head<3>()) > wider) {
      patch = widestPatch(points, members, plane.head<3>(), part_diameter);
    }
    if (!(patch.width > wider + 2.0 * patch.cell)) {
      remaining = std::move(rest);  // a face of the part: kept, and out of the next search
      continue;
    }
    // The part lies on the side of the support where most of the rest is: what lies behind the
    // band (the support's noise tail, whatever is below it) goes with it.
    std::size_t above = 0;
    for (const int i : rest) {
      above += plane.head<3>().dot(points[static_cast<std::size_t>(i)]) + plane[3] > 0.0 ? 1 : 0;
    }
    const double side = 2 * above >= rest.size() ? 1.0 : -1.0;
    std::vector<int> kept;
    SupportPlane support{side * plane, 0, patch.width};
    for (const int i : remaining) {
      const Eigen::Vector3d& p = points[static_cast<std::size_t>(i)];
      if (support.plane.head<3>().dot(p) + support.plane[3] <= band) {
        result.on_support[static_cast<std::size_t>(i)] = 1;
        ++support.points;
      } else {
        kept.push_back(i);
      }
    }
    result.removed += support.points;
    result.planes.push_back(support);
    remaining = std::move(kept);
  }
  return result;
}

}  // namespace freeform_inspection
