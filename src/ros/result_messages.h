// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <string>

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include "freeform_inspection/pipeline.h"
#include <freeform_inspection/InspectionReport.h>

/// Result → messages for rviz and the report: the deviation cloud, defect markers, and the
/// deviation and defect parts of the report.
namespace freeform_inspection_ros {

namespace fi = freeform_inspection;

/// @brief The deviation map as a PointCloud2 in the part (CAD) frame `header.frame_id`:
/// FLOAT32 x, y, z, deviation [m] (NaN where no CAD is near), UINT8 in_tolerance, INT32 region
/// (index into the report's regions, −1 for the rest of the part and unmatched points), and rgb
/// (packed FLOAT32, the banded colour scale of deviation_colours.h). At most `max_points`
/// points, taken evenly (0 = all); unorganized (height 1). `tolerance`: each point's band
/// (regions.h's toleranceBands()) or the part's.
sensor_msgs::PointCloud2 deviationCloud(const fi::InspectionResult& result,
                                        const fi::ToleranceBands& tolerance,
                                        const std_msgs::Header& header,
                                        std::size_t max_points);

/// @brief One sphere (at the centroid, sized by the area, red for excess, blue for missing
/// material) and one text label per defect region, in the part frame; the first marker
/// deletes the previous inspection's markers.
visualization_msgs::MarkerArray defectMarkers(const fi::InspectionResult& result,
                                              const std_msgs::Header& header);

/// @brief The report's part pose with its covariance, as a localizer publishes one: header =
/// the scan's frame and stamp, pose = `transform`, covariance = `pose_covariance`.
geometry_msgs::PoseWithCovarianceStamped poseWithCovariance(
    const freeform_inspection::InspectionReport& report);

/// @brief Copies statistics, histogram and defect regions into the report.
void fillDeviation(const fi::InspectionResult& result,
                   freeform_inspection::InspectionReport* report);

}  // namespace freeform_inspection_ros
