// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "result_messages.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include <sensor_msgs/point_cloud2_iterator.h>

#include "freeform_inspection/deviation_colours.h"

namespace freeform_inspection_ros {
namespace {

geometry_msgs::Point toPoint(const Eigen::Vector3d& p) {
  geometry_msgs::Point point;
  point.x = p.x();
  point.y = p.y();
  point.z = p.z();
  return point;
}

// rviz reads "rgb" as a float whose bytes are 0x00RRGGBB.
float packRgb(const fi::Rgb& colour) {
  const std::uint32_t packed = (static_cast<std::uint32_t>(colour[0]) << 16U) |
                               (static_cast<std::uint32_t>(colour[1]) << 8U) |
                               static_cast<std::uint32_t>(colour[2]);
  float value = 0.0F;
  std::memcpy(&value, &packed, sizeof(value));
  return value;
}

}  // namespace

sensor_msgs::PointCloud2 deviationCloud(const fi::InspectionResult& result,
                                        const fi::ToleranceBands& tolerance,
                                        const std_msgs::Header& header,
                                        std::size_t max_points) {
  const fi::DeviationMap& map = result.deviation_map;
  const std::size_t total = map.size();
  const std::size_t count = max_points == 0 ? total : std::min(total, max_points);
  sensor_msgs::PointCloud2 cloud;
  cloud.header = header;
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  modifier.setPointCloud2Fields(7,
                                "x",
                                1,
                                sensor_msgs::PointField::FLOAT32,
                                "y",
                                1,
                                sensor_msgs::PointField::FLOAT32,
                                "z",
                                1,
                                sensor_msgs::PointField::FLOAT32,
                                "deviation",
                                1,
                                sensor_msgs::PointField::FLOAT32,
                                "in_tolerance",
                                1,
                                sensor_msgs::PointField::UINT8,
                                "region",
                                1,
                                sensor_msgs::PointField::INT32,
                                "rgb",
                                1,
                                sensor_msgs::PointField::FLOAT32);
  modifier.resize(count);
  cloud.is_dense = false;  // deviation may be NaN
  sensor_msgs::PointCloud2Iterator<float> xyz(cloud, "x");
  sensor_msgs::PointCloud2Iterator<float> deviation(cloud, "deviation");
  sensor_msgs::PointCloud2Iterator<std::uint8_t> inside(cloud, "in_tolerance");
  sensor_msgs::PointCloud2Iterator<std::int32_t> region(cloud, "region");
  sensor_msgs::PointCloud2Iterator<float> rgb(cloud, "rgb");
  for (std::size_t k = 0; k < count; ++k, ++xyz, ++deviation, ++inside, ++region, ++rgb) {
    const std::size_t i = k * total / count;  // even stride over the scan
    xyz[0] = static_cast<float>(map.points[i].x());
    xyz[1] = static_cast<float>(map.points[i].y());
    xyz[2] = static_cast<float>(map.points[i].z());
    const double d = map.deviation[i];
    *deviation = static_cast<float>(d);
    *inside = fi::inTolerance(d, tolerance.at(i)) ? 1 : 0;
    *region = map.region.empty() ? -1 : map.region[i];
    *rgb = packRgb(fi::deviationColour(d, tolerance.at(i)));
  }
  return cloud;
}

visualization_msgs::MarkerArray defectMarkers(const fi::InspectionResult& result,
                                              const std_msgs::Header& header) {
  visualization_msgs::MarkerArray markers;
  visualization_msgs::Marker clear;
  clear.header = header;
  clear.action = visualization_msgs::Marker::DELETEALL;
  markers.markers.push_back(clear);
  int id = 0;
  for (const fi::DefectRegion& defect : result.defects) {
    visualization_msgs::Marker sphere;
    sphere.header = header;
    sphere.ns = "defects";
    sphere.id = id;
    sphere.type = visualization_msgs::Marker::SPHERE;
    sphere.action = visualization_msgs::Marker::ADD;
    sphere.pose.position = toPoint(defect.centroid);
    sphere.pose.orientation.w = 1.0;
    // The disc of the region's area, as a ball: visible, and about the defect's size.
    const double diameter = std::max(2.0 * std::sqrt(defect.area / M_PI), 1e-4);
    sphere.scale.x = sphere.scale.y = sphere.scale.z = diameter;
    sphere.color.a = 0.5F;
    sphere.color.r = defect.sign > 0 ? 1.0F : 0.0F;
    sphere.color.b = defect.sign > 0 ? 0.0F : 1.0F;
    markers.markers.push_back(sphere);
    visualization_msgs::Marker label = sphere;
    label.ns = "defect_labels";
    label.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
    label.pose.position.z += diameter;
    label.scale.x = label.scale.y = 0.0;
    label.scale.z = std::max(0.3 * diameter, 1e-3);
    label.color.r = label.color.g = label.color.b = label.color.a = 1.0F;
    char text[64];
    std::snprintf(text, sizeof(text), "#%d %+.3f mm", id, defect.peak * 1e3);
    label.text = text;
    markers.markers.push_back(label);
    ++id;
  }
  return markers;
}

geometry_msgs::PoseWithCovarianceStamped poseWithCovariance(
    const freeform_inspection::InspectionReport& report) {
  geometry_msgs::PoseWithCovarianceStamped pose;
  pose.header = report.transform.header;
  pose.pose.pose.position.x = report.transform.transform.translation.x;
  pose.pose.pose.position.y = report.transform.transform.translation.y;
  pose.pose.pose.position.z = report.transform.transform.translation.z;
  pose.pose.pose.orientation = report.transform.transform.rotation;
  pose.pose.covariance = report.pose_covariance;
  return pose;
}

namespace {

freeform_inspection::DeviationStats deviationStats(const fi::DeviationStatistics& s) {
  freeform_inspection::DeviationStats out;
  out.n_points = static_cast<std::uint32_t>(s.evaluated);
  out.n_unmatched = static_cast<std::uint32_t>(s.unmatched);
  out.n_excluded = static_cast<std::uint32_t>(s.excluded);
  out.mean = s.mean;
  out.std = s.std;
  out.rms = s.rms;
  out.min = s.min;
  out.max = s.max;
  out.p5 = s.p5;
  out.p50 = s.p50;
  out.p95 = s.p95;
  out.in_tolerance_fraction = s.in_tolerance_fraction;
  out.coverage = s.coverage;
  out.histogram_edges = s.histogram_edges;
  out.histogram_counts.assign(s.histogram_counts.begin(), s.histogram_counts.end());
  return out;
}

std::uint8_t verdictCode(fi::Verdict verdict) {
  using Report = freeform_inspection::InspectionReport;
  switch (verdict) {
    case fi::Verdict::kPass:
      return Report::PASS;
    case fi::Verdict::kFail:
      return Report::FAIL;
    default:
      return Report::NOT_EVALUATED;
  }
}

}  // namespace

void fillDeviation(const fi::InspectionResult& result,
                   freeform_inspection::InspectionReport* report) {
  const fi::DeviationStatistics& s = result.deviation;
  report->deviation = deviationStats(s);
  // Points on regions left out lie on the CAD too.
  const std::size_t scanned = result.counts.scan_points;
  report->overlap =
      scanned > 0 ? static_cast<double>(s.evaluated + s.excluded) / static_cast<double>(scanned)
                  : 0.0;
  for (const fi::RegionResult& region : result.regions) {
    freeform_inspection::RegionReport message;
    message.name = region.name;
    message.evaluated = region.evaluated;
    message.status = verdictCode(region.verdict);
    message.message = region.verdict_reason;
    message.tolerance_upper = region.tolerance.upper;
    message.tolerance_lower = region.tolerance.lower;
    message.defects = static_cast<std::uint32_t>(region.defects);
    message.deviation = deviationStats(region.deviation);
    report->regions.push_back(message);
  }
  for (const fi::ComparisonPointResult& point : result.comparison_points) {
    freeform_inspection::ComparisonPointReport message;
    message.name = point.name;
    message.datum = point.datum;
    message.status = verdictCode(point.verdict);
    message.message = point.verdict_reason;
    message.nominal.x = point.nominal.x();
    message.nominal.y = point.nominal.y();
    message.nominal.z = point.nominal.z();
    message.normal.x = point.normal.x();
    message.normal.y = point.normal.y();
    message.normal.z = point.normal.z();
    message.tolerance_upper = point.tolerance.upper;
    message.tolerance_lower = point.tolerance.lower;
    message.points = static_cast<std::uint32_t>(point.points);
    message.deviation = point.deviation;
    message.spread = point.spread;
    report->comparison_points.push_back(message);
  }
  std::uint32_t id = 0;
  for (const fi::DefectRegion& defect : result.defects) {
    freeform_inspection::Defect message;
    message.id = id++;
    message.sign = static_cast<std::int8_t>(defect.sign);
    message.points = static_cast<std::uint32_t>(defect.points);
    message.area = defect.area;
    message.peak = defect.peak;
    message.mean = defect.mean;
    message.centroid = toPoint(defect.centroid);
    message.bbox_min = toPoint(defect.bbox_min);
    message.bbox_max = toPoint(defect.bbox_max);
    message.cad_chord_error = defect.cad_chord_error;
    message.region = result.regionName(defect.region);
    report->defects.push_back(message);
  }
}

}  // namespace freeform_inspection_ros
