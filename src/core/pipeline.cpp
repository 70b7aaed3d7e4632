// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/pipeline.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "freeform_inspection/organized_mesh.h"

namespace freeform_inspection {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Organized scans (range images) carry their connectivity: triangulate on the grid, before the
// non-finite pixels are removed, so the scan is a mesh like the CAD.
CleanScanResult cleanWithGridFaces(const Scan& scan,
                                   const BoundingBox& model_bounds,
                                   const InputConfig& config) {
  if (!scan.isOrganized() || !scan.faces.empty()) {
    return cleanScan(scan, model_bounds, config);
  }
  Scan meshed = scan;
  meshed.faces =
      triangulateOrganizedGrid(scan.points, scan.width, scan.height, OrganizedMeshConfig());
  return cleanScan(meshed, model_bounds, config);
}

}  // namespace

const char* toString(RegistrationStatus status) {
  switch (status) {
    case RegistrationStatus::kOk:
      return "ok";
    case RegistrationStatus::kAmbiguous:
      return "ambiguous";
    case RegistrationStatus::kFailed:
      return "failed";
  }
  return "failed";
}

const char* toString(Verdict verdict) {
  switch (verdict) {
    case Verdict::kPass:
      return "PASS";
    case Verdict::kFail:
      return "FAIL";
    case Verdict::kNotEvaluated:
      return "NOT_EVALUATED";
  }
  return "NOT_EVALUATED";
}

std::vector<std::string> validate(const PipelineConfig& config) {
  std::vector<std::string> errors;
  const InputConfig& input = config.input;
  if (input.min_points < 3) {
    errors.push_back("input.min_points must be at least 3");
  }
  if (input.max_points < input.min_points) {
    errors.push_back("input.max_points must be at least input.min_points");
  }
  if (!(input.max_extent_ratio > 1.0)) {
    errors.push_back("input.max_extent_ratio must be > 1");
  }
  if (!(input.min_thickness_ratio >= 0.0 && input.min_thickness_ratio < 1.0)) {
    errors.push_back("input.min_thickness_ratio must be in [0, 1)");
  }
  for (const auto& error : validate(config.descriptor)) {
    errors.push_back(error);
  }
  if (!(config.tolerance.upper > 0.0 && std::isfinite(config.tolerance.upper))) {
    errors.push_back("tolerance.upper must be a finite length > 0 [m]");
  }
  if (!(config.tolerance.lower < 0.0 && std::isfinite(config.tolerance.lower))) {
    errors.push_back("tolerance.lower must be a finite length < 0 [m]");
  }
  return errors;
}

InspectionResult inspect(const Model& model, const Scan& scan, const PipelineConfig& config) {
  const auto errors = validate(config);
  if (!errors.empty()) {
    throw std::invalid_argument("invalid pipeline configuration: " + joinMessages(errors));
  }
  const auto start = Clock::now();
  InspectionResult result;
  result.counts.cad_vertices = model.mesh().vertices.size();

  const auto clean_start = Clock::now();
  const CleanScanResult cleaned = cleanWithGridFaces(scan, model.bounds(), config.input);
  result.timings.push_back({"clean", secondsSince(clean_start)});
  result.counts.scan_points = cleaned.scan.points.size();
  result.counts.non_finite = cleaned.non_finite;
  result.counts.scan_faces = cleaned.scan.faces.size();
  result.status = cleaned.status;
  if (result.status.ok()) {
    const auto descriptor_start = Clock::now();
    // The CAD's radii, so a partial scan gets the same descriptor as the full part.
    const DescriptorResult descriptors = computeDescriptors(cleaned.scan.points,
                                                            cleaned.scan.faces,
                                                            cleaned.scan.normals,
                                                            model.descriptors().radii,
                                                            config.descriptor);
    result.timings.push_back({"descriptors", secondsSince(descriptor_start)});
    result.status = descriptors.status;
  }
  if (result.status.ok()) {
    // Feature selection, correspondences and registration land with the registration work;
    // until then the pipeline says so rather than return an identity pose that looks like an
    // answer.
    result.status = Status::failure(StatusCode::kNotImplemented,
                                    "registration is not implemented yet: no pose computed");
  }
  result.timings.push_back({"total", secondsSince(start)});
  return result;
}

}  // namespace freeform_inspection
