// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstdint>
#include <string>

#include "cloud_conversion.h"  // CloudConversion, cloudToScan
#include <pcl_msgs/PolygonMesh.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/Header.h>
#include <visualization_msgs/Marker.h>

#include "freeform_inspection/model.h"
#include "freeform_inspection/pipeline.h"
#include <freeform_inspection/InspectionReport.h>

/// The only place where ROS messages meet core types.
namespace freeform_inspection_ros {

namespace fi = freeform_inspection;

/// @brief "PASS", "FAIL", "NOT_EVALUATED" or "ERROR" for an InspectionReport status.
const char* statusName(std::uint8_t status);

/// @brief Upper-case machine-readable name of a status code, e.g. "INVALID_INPUT".
std::string errorCode(fi::StatusCode code);

/// @brief A stamped mesh (pcl_msgs/PolygonMesh, as pcl_conversions writes one) read into a scan:
/// the vertices by cloudToScan(), each polygon of three or more vertices fanned into triangles.
/// Refused (kInvalidInput) for a cloud cloudToScan() refuses, a polygon of fewer than three
/// vertices or one that names a vertex the cloud does not have. The faces define the surface, so
/// a grid layout of the vertex cloud is dropped.
CloudConversion meshToScan(const pcl_msgs::PolygonMesh& mesh);

/// @brief A scan as an x, y, z FLOAT32 cloud with `header`: organized (width × height, NaN kept)
/// when the scan is, else one row; `is_dense` is false when any point is not finite. Normals and
/// faces are not converted.
sensor_msgs::PointCloud2 scanToCloud(const fi::Scan& scan, const std_msgs::Header& header);

/// @brief The CAD mesh as a TRIANGLE_LIST marker in `frame` (published once, latched).
visualization_msgs::Marker modelMarker(const fi::Model& model, const std::string& frame);

/// @brief A report for a request refused before the pipeline ran (no model, no scan, ...).
freeform_inspection::InspectionReport errorReport(const std::string& error_code,
                                                  const std::string& message);

/// error_code of an inspection cancelled through the action.
inline constexpr char kCancelledCode[] = "CANCELLED";

/// @brief The report of an inspection cancelled `when` (e.g. "before the inspection started"):
/// status ERROR, error_code CANCELLED, the scan's header; nothing of that run is published.
freeform_inspection::InspectionReport cancelledReport(const std::string& when,
                                                      const std_msgs::Header& scan_header);

/// @brief The pipeline's result as a report message. The transform is the part pose in the scan
/// frame: parent = `scan_frame`, child = `part_frame`, value = inverse(T_cad_scan).
freeform_inspection::InspectionReport toReport(const fi::InspectionResult& result,
                                               const std_msgs::Header& scan_header,
                                               const std::string& part_frame);

}  // namespace freeform_inspection_ros
