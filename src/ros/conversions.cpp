// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "conversions.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <limits>

#include "result_messages.h"
#include <tf2_eigen/tf2_eigen.h>

namespace freeform_inspection_ros {
namespace {

using sensor_msgs::PointField;

}  // namespace

const char* statusName(std::uint8_t status) {
  using Report = freeform_inspection::InspectionReport;
  switch (status) {
    case Report::PASS:
      return "PASS";
    case Report::FAIL:
      return "FAIL";
    case Report::NOT_EVALUATED:
      return "NOT_EVALUATED";
    default:
      return "ERROR";
  }
}

std::string errorCode(fi::StatusCode code) {
  std::string text = fi::toString(code);
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) {
    return static_cast<char>(std::toupper(c));
  });
  return text;
}

sensor_msgs::PointCloud2 scanToCloud(const fi::Scan& scan, const std_msgs::Header& header) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header = header;
  const bool organized = scan.isOrganized();
  cloud.width = static_cast<std::uint32_t>(organized ? scan.width : scan.points.size());
  cloud.height = organized ? static_cast<std::uint32_t>(scan.height) : 1U;
  const char* names[] = {"x", "y", "z"};
  for (std::uint32_t i = 0; i < 3; ++i) {
    PointField field;
    field.name = names[i];
    field.offset = i * static_cast<std::uint32_t>(sizeof(float));
    field.datatype = PointField::FLOAT32;
    field.count = 1;
    cloud.fields.push_back(field);
  }
  cloud.is_bigendian = false;
  cloud.point_step = 3 * static_cast<std::uint32_t>(sizeof(float));
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.data.resize(std::size_t{cloud.row_step} * cloud.height);
  cloud.is_dense = true;
  std::uint8_t* out = cloud.data.data();
  for (const Eigen::Vector3d& p : scan.points) {
    const float xyz[3] = {
        static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
    std::memcpy(out, xyz, sizeof(xyz));
    out += sizeof(xyz);
    cloud.is_dense = cloud.is_dense && p.allFinite();
  }
  return cloud;
}

visualization_msgs::Marker modelMarker(const fi::Model& model, const std::string& frame) {
  visualization_msgs::Marker marker;
  marker.header.frame_id = frame;
  marker.ns = "cad";
  marker.id = 0;
  marker.type = visualization_msgs::Marker::TRIANGLE_LIST;
  marker.action = visualization_msgs::Marker::ADD;
  marker.pose.orientation.w = 1.0;
  marker.scale.x = marker.scale.y = marker.scale.z = 1.0;
  marker.color.r = marker.color.g = marker.color.b = 0.7F;
  marker.color.a = 0.6F;
  const auto& mesh = model.mesh();
  marker.points.reserve(mesh.faces.size() * 3);
  for (const auto& face : mesh.faces) {
    for (int corner = 0; corner < 3; ++corner) {
      geometry_msgs::Point p;
      p.x = mesh.vertices[static_cast<std::size_t>(face[corner])].x();
      p.y = mesh.vertices[static_cast<std::size_t>(face[corner])].y();
      p.z = mesh.vertices[static_cast<std::size_t>(face[corner])].z();
      marker.points.push_back(p);
    }
  }
  return marker;
}

freeform_inspection::InspectionReport errorReport(const std::string& error_code,
                                                  const std::string& message) {
  freeform_inspection::InspectionReport report;
  report.status = freeform_inspection::InspectionReport::ERROR;
  report.error_code = error_code;
  report.message = message;
  report.registration_status = fi::toString(fi::RegistrationStatus::kFailed);
  report.transform.transform.rotation.w = 1.0;
  report.best_fit_transform.rotation.w = 1.0;
  report.alignment = "best_fit";
  // Unknown, as the other quantities a refused request never measured say with NaN.
  report.offset_from_guess_deg = std::numeric_limits<double>::quiet_NaN();
  report.offset_from_guess = std::numeric_limits<double>::quiet_NaN();
  report.pose_rotation_std_deg = std::numeric_limits<double>::quiet_NaN();
  report.pose_translation_std = std::numeric_limits<double>::quiet_NaN();
  return report;
}

freeform_inspection::InspectionReport cancelledReport(const std::string& when,
                                                      const std_msgs::Header& scan_header) {
  freeform_inspection::InspectionReport report =
      errorReport(kCancelledCode, "cancelled " + when + "; nothing was published");
  report.header = scan_header;
  return report;
}

freeform_inspection::InspectionReport toReport(const fi::InspectionResult& result,
                                               const std_msgs::Header& scan_header,
                                               const std::string& part_frame) {
  using Report = freeform_inspection::InspectionReport;
  Report report;
  report.header = scan_header;
  report.registration_status = fi::toString(result.registration);
  // ERROR is for input the pipeline could not use; a scan that was read but not registered
  // (or registered ambiguously) is NOT_EVALUATED, with the reason and its code.
  const fi::StatusCode code = result.status.code;
  const bool bad_input = code == fi::StatusCode::kInvalidInput ||
                         code == fi::StatusCode::kDegenerateInput ||
                         code == fi::StatusCode::kUnitsMismatch;
  if (bad_input) {
    report.status = Report::ERROR;
    report.message = result.status.message;
  } else if (result.verdict == fi::Verdict::kPass) {
    report.status = Report::PASS;
    report.message = result.verdict_reason;
  } else if (result.verdict == fi::Verdict::kFail) {
    report.status = Report::FAIL;
    report.message = result.verdict_reason;
  } else {
    report.status = Report::NOT_EVALUATED;
    report.message = result.verdict_reason.empty() ? result.status.message : result.verdict_reason;
  }
  if (!result.status.ok()) {
    report.error_code = errorCode(code);
  }
  report.transform = tf2::eigenToTransform(result.T_cad_scan.inverse());
  report.transform.header = scan_header;
  report.transform.child_frame_id = part_frame;
  report.rmse = result.rmse;
  report.fitness = result.fitness;
  report.ambiguity = result.ambiguity;
  report.offset_from_guess_deg = result.offset_from_initial_deg;
  report.offset_from_guess = result.offset_from_initial;
  const fi::DatumAlignment& datums = result.datum_alignment;
  report.alignment = result.registration == fi::RegistrationStatus::kFixed ? "fixed"
                     : !datums.requested                                   ? "best_fit"
                     : datums.aligned                                      ? "datums"
                                                                           : "datums_failed";
  report.alignment_message = datums.message;
  report.best_fit_transform =
      tf2::eigenToTransform(
          (datums.requested ? datums.T_cad_scan_best_fit : result.T_cad_scan).inverse())
          .transform;
  const fi::PoseUncertainty& spread = result.pose_uncertainty;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      report.pose_covariance[static_cast<std::size_t>(6 * r + c)] =
          spread.known ? spread.covariance(r, c) : 0.0;
    }
  }
  report.pose_rotation_std_deg = spread.rotation_deg;
  report.pose_translation_std = spread.translation;
  report.counts.scan_points = static_cast<std::uint32_t>(result.counts.scan_points);
  report.counts.cropped = static_cast<std::uint32_t>(result.counts.cropped);
  report.counts.support_points = static_cast<std::uint32_t>(result.counts.support_points);
  report.counts.scan_faces = static_cast<std::uint32_t>(result.counts.scan_faces);
  report.counts.cad_vertices = static_cast<std::uint32_t>(result.counts.cad_vertices);
  report.counts.features = static_cast<std::uint32_t>(result.counts.features);
  report.counts.candidates = static_cast<std::uint32_t>(result.counts.candidates);
  report.counts.correspondences = static_cast<std::uint32_t>(result.counts.correspondences);
  fillDeviation(result, &report);
  report.deviation.n_invalid = static_cast<std::uint32_t>(result.counts.non_finite);
  for (const auto& timing : result.timings) {
    freeform_inspection::Timing stage;
    stage.stage = timing.stage;
    stage.seconds = timing.seconds;
    report.timings.push_back(stage);
  }
  return report;
}

}  // namespace freeform_inspection_ros
