// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// Visibility votes on the orientation of a cloud's normals: orthographic depth images from
// antipodal pairs of directions; a point at the front of an image is seen from that direction,
// and its outward normal must face it.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "cloud_visibility_internal.h"
#include "large_buffer_internal.h"
#include <Eigen/Geometry>

namespace freeform_inspection {
namespace internal {
namespace {

// A normal this close to perpendicular to the direction says nothing about the side (a wall
// seen edge-on).
constexpr double kMinFacing = 0.2;

// Direction k of n spread evenly over the upper hemisphere (a Fibonacci spiral); each is used
// with its opposite.
Eigen::Vector3d spiralDirection(int k, int n) {
  const double golden_angle = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (k + 0.5) / n;
  const double r = std::sqrt(1.0 - z * z);
  return {r * std::cos(golden_angle * k), r * std::sin(golden_angle * k), z};
}

// Per-thread buffers of the depth images, kept across directions.
struct DepthScratch {
  LargeVector<std::size_t> pixel;
  LargeVector<double> front;
};

// Points seen from `direction` and from its opposite (the viewer at +infinity along each):
// within the tolerance of the front-most point of their pixel. Both images share the pixels, so
// one pass projects the points and keeps the nearest depth from either side. Each point's facing
// is added to `facing` / `away`.
void voteFromDirectionPair(const Points& points,
                           const Points& normals,
                           const Eigen::Vector3d& direction,
                           const VisibilityConfig& config,
                           DepthScratch& scratch,
                           std::vector<int>* facing,
                           std::vector<int>* away) {
  const Eigen::Vector3d u = direction.unitOrthogonal();
  const Eigen::Vector3d v = direction.cross(u);
  double u_min = std::numeric_limits<double>::infinity();
  double v_min = u_min;
  double u_max = -u_min;
  double v_max = -u_min;
  for (const Eigen::Vector3d& p : points) {
    u_min = std::min(u_min, p.dot(u));
    u_max = std::max(u_max, p.dot(u));
    v_min = std::min(v_min, p.dot(v));
    v_max = std::max(v_max, p.dot(v));
  }
  const auto width = static_cast<std::size_t>((u_max - u_min) / config.pixel) + 1;
  const auto height = static_cast<std::size_t>((v_max - v_min) / config.pixel) + 1;
  scratch.pixel.resize(points.size());
  // front[2 q] is the largest depth along +direction in pixel q, front[2 q + 1] along −direction.
  scratch.front.assign(2 * width * height, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto x = static_cast<std::size_t>((points[i].dot(u) - u_min) / config.pixel);
    const auto y = static_cast<std::size_t>((points[i].dot(v) - v_min) / config.pixel);
    const std::size_t q = std::min(y, height - 1) * width + std::min(x, width - 1);
    scratch.pixel[i] = q;
    const double depth = points[i].dot(direction);
    scratch.front[2 * q] = std::max(scratch.front[2 * q], depth);
    scratch.front[2 * q + 1] = std::max(scratch.front[2 * q + 1], -depth);
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double depth = points[i].dot(direction);
    const double cosine = normals[i].dot(direction);
    const std::size_t q = scratch.pixel[i];
    // Seen from +direction, then from −direction (where depth and facing change sign).
    if (!(depth < scratch.front[2 * q] - config.depth_tolerance)) {
      (*facing)[i] += cosine > kMinFacing ? 1 : 0;
      (*away)[i] += cosine < -kMinFacing ? 1 : 0;
    }
    if (!(-depth < scratch.front[2 * q + 1] - config.depth_tolerance)) {
      (*facing)[i] += -cosine > kMinFacing ? 1 : 0;
      (*away)[i] += -cosine < -kMinFacing ? 1 : 0;
    }
  }
}

// A depth image holds at most this many pixels per point, plus a floor: a far stray point
// would otherwise stretch the image to billions of pixels.
constexpr double kPixelsPerPoint = 4.0;
constexpr double kMinPixelBudget = 1 << 20;

// The pixel widened (and the tolerance with it) until an image over the points' bounding
// sphere fits the budget.
VisibilityConfig boundedImages(const Points& points, const VisibilityConfig& config) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) {
    centre += p / double(points.size());
  }
  double radius = 0.0;
  for (const Eigen::Vector3d& p : points) {
    radius = std::max(radius, (p - centre).norm());
  }
  const double budget = std::max(kMinPixelBudget, kPixelsPerPoint * double(points.size()));
  const double side = 2.0 * radius / std::sqrt(budget);
  VisibilityConfig bounded = config;
  if (side > config.pixel) {
    bounded.depth_tolerance += side - config.pixel;
    bounded.pixel = side;
  }
  return bounded;
}

}  // namespace

std::vector<signed char> visibilityVotes(const Points& points,
                                         const Points& normals,
                                         const VisibilityConfig& config) {
  const std::size_t count = points.size();
  if (!(config.pixel > 0.0) || config.direction_pairs < 1) {
    return std::vector<signed char>(count, 0);
  }
  const VisibilityConfig bounded = boundedImages(points, config);
  std::vector<int> facing(count, 0);
  std::vector<int> away(count, 0);
#pragma omp parallel
  {
    std::vector<int> my_facing(count, 0);
    std::vector<int> my_away(count, 0);
    DepthScratch scratch;
#pragma omp for schedule(dynamic, 1)
    for (int k = 0; k < config.direction_pairs; ++k) {
      voteFromDirectionPair(points,
                            normals,
                            spiralDirection(k, config.direction_pairs),
                            bounded,
                            scratch,
                            &my_facing,
                            &my_away);
    }
#pragma omp critical
    for (std::size_t i = 0; i < count; ++i) {  // integer sums: the order does not matter
      facing[i] += my_facing[i];
      away[i] += my_away[i];
    }
  }
  std::vector<signed char> votes(count, 0);
  for (std::size_t i = 0; i < count; ++i) {
    if (facing[i] >= 2 && away[i] == 0) {
      votes[i] = 1;
    } else if (away[i] >= 2 && facing[i] == 0) {
      votes[i] = -1;
    }
  }
  return votes;
}

}  // namespace internal
}  // namespace freeform_inspection
