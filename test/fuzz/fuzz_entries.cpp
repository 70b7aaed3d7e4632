// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "fuzz_entries.h"

#include <cmath>
#include <string>
#include <variant>

#include "fuzz_input_file.h"
#include <pcl/console/print.h>

#include "freeform_inspection/config_fields.h"
#include "freeform_inspection/config_yaml.h"
#include "freeform_inspection/io.h"

namespace freeform_inspection {
namespace fuzz {
namespace {

bool allFinite(const Points& points) {
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) {
      return false;
    }
  }
  return true;
}

bool facesInRange(const Triangles& faces, std::size_t vertices) {
  for (const Eigen::Vector3i& f : faces) {
    for (int c = 0; c < 3; ++c) {
      if (f[c] < 0 || static_cast<std::size_t>(f[c]) >= vertices) {
        return false;
      }
    }
  }
  return true;
}

void checkStatus(const Status& status, EntryOutcome* outcome) {
  outcome->ok = outcome->ok && status.ok();
  if (!status.ok()) {
    outcome->message += (outcome->message.empty() ? "" : " | ") + status.message;
    if (status.message.empty()) {
      markBroken(outcome, "failure without a message");
    }
  }
}

// A loaded mesh is usable as a CAD model: faces, finite vertices, indices in range.
void checkMesh(const MeshLoadResult& result, EntryOutcome* outcome) {
  checkStatus(result.status, outcome);
  if (!result.status.ok()) {
    return;
  }
  const TriangleMesh& mesh = result.mesh;
  if (mesh.faces.empty()) {
    markBroken(outcome, "mesh loaded without faces");
  }
  if (!allFinite(mesh.vertices)) {
    markBroken(outcome, "mesh with a non-finite vertex");
  }
  if (!facesInRange(mesh.faces, mesh.vertices.size())) {
    markBroken(outcome, "mesh face index out of range");
  }
  if (mesh.face_normals.size() != mesh.faces.size() || !allFinite(mesh.face_normals)) {
    markBroken(outcome, "mesh face normals missing or not finite");
  }
}

// A loaded scan: finite points (NaN only inside an organized grid), matching normals and faces.
void checkScan(const ScanLoadResult& result, EntryOutcome* outcome) {
  checkStatus(result.status, outcome);
  if (!result.status.ok()) {
    return;
  }
  const Scan& scan = result.scan;
  if (scan.points.empty()) {
    markBroken(outcome, "scan loaded without points");
  }
  const bool grid = scan.width != 0 || scan.height != 0;
  if (grid && !scan.isOrganized()) {
    markBroken(outcome, "scan grid does not match its points");
  }
  if (!grid && !allFinite(scan.points)) {
    markBroken(outcome, "unorganized scan with a non-finite point");
  }
  if (!scan.normals.empty() &&
      (scan.normals.size() != scan.points.size() || !allFinite(scan.normals))) {
    markBroken(outcome, "scan normals do not match the points or are not finite");
  }
  if (!facesInRange(scan.faces, scan.points.size())) {
    markBroken(outcome, "scan face index out of range");
  }
}

EntryOutcome loadAsMesh(const std::uint8_t* data, std::size_t size, const char* extension) {
  EntryOutcome outcome;
  outcome.ok = true;
  const InputFile file(data, size, extension);
  checkMesh(loadMesh(file.path(), 1.0), &outcome);
  return outcome;
}

EntryOutcome loadAsScan(const std::uint8_t* data, std::size_t size, const char* extension) {
  EntryOutcome outcome;
  outcome.ok = true;
  const InputFile file(data, size, extension);
  checkScan(loadScan(file.path(), 1.0), &outcome);
  return outcome;
}

// Formats that are both CAD and scan formats go through both loaders: same reader, different
// post-processing.
EntryOutcome loadAsMeshAndScan(const std::uint8_t* data, std::size_t size, const char* extension) {
  EntryOutcome outcome;
  outcome.ok = true;
  const InputFile file(data, size, extension);
  checkMesh(loadMesh(file.path(), 1.0), &outcome);
  checkScan(loadScan(file.path(), 1.0), &outcome);
  return outcome;
}

}  // namespace

EntryOutcome fuzzStl(const std::uint8_t* data, std::size_t size) {
  return loadAsMeshAndScan(data, size, ".stl");
}

EntryOutcome fuzzPlyMesh(const std::uint8_t* data, std::size_t size) {
  return loadAsMesh(data, size, ".ply");
}

EntryOutcome fuzzPlyScan(const std::uint8_t* data, std::size_t size) {
  return loadAsScan(data, size, ".ply");
}

EntryOutcome fuzzObj(const std::uint8_t* data, std::size_t size) {
  return loadAsMeshAndScan(data, size, ".obj");
}

EntryOutcome fuzzPcd(const std::uint8_t* data, std::size_t size) {
  // PCL reports every malformed header on stderr; at thousands of inputs a second that is most
  // of the time spent.
  static const bool quiet = [] {
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    return true;
  }();
  static_cast<void>(quiet);
  return loadAsScan(data, size, ".pcd");
}

EntryOutcome fuzzConfigYaml(const std::uint8_t* data, std::size_t size) {
  EntryOutcome outcome;
  ConfigLoadResult result =
      parsePipelineConfig(std::string(reinterpret_cast<const char*>(data), size));
  outcome.ok = true;
  checkStatus(result.status, &outcome);
  if (outcome.ok) {
    // A configuration that validated must not carry a NaN: every check on it would pass.
    for (const ConfigField& field : configFields(result.config)) {
      const auto* value = std::get_if<double*>(&field.target);
      if (value != nullptr && std::isnan(**value)) {
        markBroken(&outcome, "configuration accepted NaN for '" + field.key + "'");
      }
    }
    if (!validate(result.config).empty()) {
      markBroken(&outcome, "configuration accepted but does not validate");
    }
  }
  return outcome;
}

const std::vector<NamedEntry>& coreEntries() {
  static const std::vector<NamedEntry> entries = {{"stl", &fuzzStl},
                                                  {"ply_mesh", &fuzzPlyMesh},
                                                  {"ply_scan", &fuzzPlyScan},
                                                  {"obj", &fuzzObj},
                                                  {"pcd", &fuzzPcd},
                                                  {"config_yaml", &fuzzConfigYaml}};
  return entries;
}

}  // namespace fuzz
}  // namespace freeform_inspection
