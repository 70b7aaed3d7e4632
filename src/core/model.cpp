// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/model.h"

#include <utility>

#include "freeform_inspection/io.h"

namespace freeform_inspection {

std::optional<double> unitScale(const std::string& units) {
  if (units == "m") {
    return 1.0;
  }
  if (units == "mm") {
    return 0.001;
  }
  if (units == "in") {
    return 0.0254;
  }
  return std::nullopt;
}

Model::Model(TriangleMesh mesh, std::string id, std::string source)
    : mesh_(std::move(mesh)),
      bounds_(computeBoundingBox(mesh_.vertices)),
      topology_(analyzeTopology(mesh_)),
      id_(std::move(id)),
      source_(std::move(source)) {}

ModelLoadResult loadModel(const std::string& path, double scale, const std::string& id) {
  ModelLoadResult result;
  MeshLoadResult loaded = loadMesh(path, scale);
  result.warnings = std::move(loaded.warnings);
  if (!loaded.status.ok()) {
    result.status = loaded.status;
    return result;
  }
  auto model = std::make_shared<const Model>(std::move(loaded.mesh), id, path);
  if (model->topology().area <= 0.0 || model->bounds().diagonal() <= 0.0) {
    result.status = Status::failure(StatusCode::kDegenerateInput,
                                    "CAD model '" + path + "' has zero surface area");
    return result;
  }
  const MeshTopology& topology = model->topology();
  if (!topology.isClosedManifold()) {
    result.warnings.push_back("CAD model '" + path + "' is not a closed, consistently oriented " +
                              "manifold (" + std::to_string(topology.boundary_edges) +
                              " boundary, " + std::to_string(topology.non_manifold_edges) +
                              " non-manifold, " + std::to_string(topology.misoriented_edges) +
                              " misoriented edges): deviation signs may be unreliable");
  }
  result.model = std::move(model);
  return result;
}

}  // namespace freeform_inspection
