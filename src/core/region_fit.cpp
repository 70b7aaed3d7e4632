// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// The best fit limited to the regions that align (docs/inspection.md, "Regions"): a surface
// left with stock for a later operation, or one the fixture bends, must not pull the pose.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pipeline_internal.h"

#include "freeform_inspection/chord_error.h"
#include "freeform_inspection/global_registration.h"
#include "freeform_inspection/icp.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/regions.h"

namespace freeform_inspection::internal {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Two rounds: the points are sorted into regions where the full fit put them, then again where
// the first restricted fit did (a region's border moves with the pose by the pose's change).
constexpr int kRounds = 2;

bool aligns(const std::vector<RegionConfig>& regions, int region) {
  return region < 0 || regions[static_cast<std::size_t>(region)].align;
}

}  // namespace

void fitToAlignedRegions(const Model& model,
                         const Points& scan_points,
                         const Points& point_normals,
                         const PipelineConfig& config,
                         InspectionResult* result) {
  const std::vector<RegionConfig>& regions = config.regions;
  if (std::all_of(regions.begin(), regions.end(), [](const RegionConfig& r) { return r.align; })) {
    return;
  }
  CurvedSurface curved;
  if (result->cad_curve_share > 0.0) {
    curved.chord = &model.chordError();
    curved.share = result->cad_curve_share;
  }
  const double diagonal = model.bounds().diagonal();
  const Eigen::Isometry3d start = result->T_cad_scan;
  const Eigen::Vector3d centroid = [&] {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : scan_points) {
      sum += p;
    }
    return Eigen::Vector3d(sum / static_cast<double>(std::max<std::size_t>(scan_points.size(), 1)));
  }();
  std::size_t used = 0;
  for (int round = 0; round < kRounds; ++round) {
    Points moved(scan_points.size());
    for (std::size_t i = 0; i < scan_points.size(); ++i) {
      moved[i] = result->T_cad_scan * scan_points[i];
    }
    const SurfaceDistances distances =
        measureDeviation(model, moved, config.deviation.max_distance_ratio * diagonal);
    const std::vector<int> region = regionOf(regions, distances.closest);
    Points subset;
    Points subset_normals;
    for (std::size_t i = 0; i < scan_points.size(); ++i) {
      if (std::isfinite(distances.deviation[i]) && aligns(regions, region[i])) {
        subset.push_back(scan_points[i]);
        if (!point_normals.empty()) {
          subset_normals.push_back(point_normals[i]);
        }
      }
    }
    if (subset.size() < std::max<std::size_t>(config.input.min_points, 3)) {
      result->warnings.push_back(
          "only " + std::to_string(subset.size()) +
          " scan points lie on regions that align (align: false leaves out the rest): the pose "
          "is the best fit to the whole scan");
      result->T_cad_scan = start;
      return;
    }
    const IcpResult fit = refinePose(model.query(),
                                     subset,
                                     result->T_cad_scan,
                                     result->inlier_distance,
                                     diagonal,
                                     config.icp,
                                     subset_normals,
                                     curved);
    if (!fit.usable()) {
      result->warnings.push_back("the best fit to the regions that align failed (" +
                                 fit.status.message +
                                 "): the pose is the best fit to the whole scan");
      result->T_cad_scan = start;
      return;
    }
    result->T_cad_scan = fit.T_cad_scan;
    result->rmse = fit.rmse;
    result->fitness = fit.fitness;
    result->inlier_distance = fit.inlier_distance;
    result->noise_sigma = fit.sigma;
    used = subset.size();
  }
  const PoseDifference moved = poseDifference(start, result->T_cad_scan, centroid);
  result->status.message += "; best fit to the regions that align, " + std::to_string(used) +
                            " of " + std::to_string(scan_points.size()) +
                            " points: " + std::to_string(moved.angle * 180.0 / kPi) + " deg and " +
                            formatLength(moved.shift) + " from the whole scan's";
}

}  // namespace freeform_inspection::internal
