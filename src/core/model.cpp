// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/model.h"

#include <cstdint>
#include <cstdio>
#include <utility>

#include "io/file_util.h"
#include "io/mesh_bytes.h"

#include "freeform_inspection/content_hash.h"
#include "freeform_inspection/io.h"

namespace freeform_inspection {
namespace {

// The settings that shape the descriptors, for the cache keys.
void addSettings(const DescriptorConfig& config, ContentHash* hash) {
  hash->add(config.scales);
  hash->add(config.max_radius_ratio);
  hash->add(config.cell_ratio);
  hash->add(config.coarse_ball_cells);
  hash->add(config.cloud_edge_neighbours);
  hash->add(config.cloud_edge_spacings);
  hash->add(config.cloud_thinning_ratio);
  hash->add(config.max_analysed_points);
  hash->add(config.mesh_curvature.method);
  hash->add(config.cloud_curvature.neighbours);
  hash->add(config.noise_fit_multiple);
  hash->add(config.max_cloud_neighbours);
  hash->add(config.noise_fit_budget);
}

std::string descriptorCacheKey(const TriangleMesh& mesh, const DescriptorConfig& config) {
  // The coordinates and corner indices as they lie in memory: x, y, z of each vertex, then the
  // three corners of each face.
  static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "packed vertices");
  static_assert(sizeof(Eigen::Vector3i) == 3 * sizeof(int), "packed faces");
  ContentHash hash;
  hash.addBytes(mesh.vertices.data(), mesh.vertices.size() * sizeof(Eigen::Vector3d));
  hash.addBytes(mesh.faces.data(), mesh.faces.size() * sizeof(Eigen::Vector3i));
  addSettings(config, &hash);
  return hash.hex();
}

// CAD exports use large triangles where the surface is flat: refine them to the descriptor
// resolution (edges no longer than a surface-graph cell) so every part of the surface has
// cells, candidates can lie anywhere and cells weigh the area they stand for.
DescriptorResult describeModel(const TriangleMesh& mesh,
                               double diagonal,
                               const DescriptorConfig& config) {
  const std::vector<double> radii = kernelRadii(diagonal, config);
  const double cell = radii.empty() ? 0.0 : config.cell_ratio * radii.front();
  constexpr std::size_t kMaxFaces = 4000000;
  const TriangleMesh refined = refineLongEdges(mesh, cell, kMaxFaces);
  return computeDescriptors(refined.vertices, refined.faces, {}, radii, config);
}

// The deviation's sign needs one outward winding everywhere, whatever the exporter wrote.
TriangleMesh orientedOutward(TriangleMesh mesh, OrientationResult* orientation) {
  *orientation = orientOutward(&mesh);
  return mesh;
}

}  // namespace

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

Model::Model(TriangleMesh mesh,
             std::string id,
             std::string source,
             const DescriptorConfig& descriptor_config)
    : mesh_(orientedOutward(std::move(mesh), &orientation_)),
      bounds_(computeBoundingBox(mesh_.vertices)),
      thickness_(principalThickness(mesh_)),
      topology_(analyzeTopology(mesh_)),
      id_(std::move(id)),
      source_(std::move(source)),
      descriptor_key_(descriptorCacheKey(mesh_, descriptor_config)),
      descriptor_config_(descriptor_config),
      query_(std::make_unique<MeshQuery>(mesh_)),
      face_border_edges_(borderEdgeMasks(mesh_)),
      chord_error_(estimateChordError(mesh_)) {
  descriptors_ = describeModel(mesh_, bounds_.diagonal(), descriptor_config);
  symmetries_ = findSymmetries(descriptors_, *query_, cellSize(), bounds_.diagonal());
  normal_frame_turns_ = freeform_inspection::normalFrameTurns(descriptors_.graph);
}

Model::Model(ModelCacheEntry entry,
             std::string id,
             std::string source,
             const DescriptorConfig& descriptor_config)
    : orientation_(entry.orientation),
      mesh_(std::move(entry.mesh)),
      bounds_(computeBoundingBox(mesh_.vertices)),
      thickness_(entry.thickness),
      topology_(entry.topology),
      id_(std::move(id)),
      source_(std::move(source)),
      descriptors_(std::move(entry.descriptors)),
      descriptor_key_(std::move(entry.descriptor_key)),
      descriptor_config_(descriptor_config),
      query_(std::make_unique<MeshQuery>(mesh_)),
      symmetries_(std::move(entry.symmetries)),
      normal_frame_turns_(std::move(entry.normal_frame_turns)),
      face_border_edges_(std::move(entry.face_border_edges)),
      chord_error_(std::move(entry.chord_error)),
      from_cache_(true) {}

ModelCacheEntry Model::cacheEntry(std::vector<std::string> load_warnings) const {
  ModelCacheEntry entry;
  entry.mesh = mesh_;
  entry.orientation = orientation_;
  entry.topology = topology_;
  entry.face_border_edges = face_border_edges_;
  entry.load_warnings = std::move(load_warnings);
  entry.descriptor_key = descriptor_key_;
  entry.descriptors = descriptors_;
  entry.symmetries = symmetries_;
  entry.chord_error = chord_error_;
  entry.thickness = thickness_;
  entry.normal_frame_turns = normal_frame_turns_;
  return entry;
}

std::string descriptorSettingsKey(const DescriptorConfig& config) {
  ContentHash hash;
  addSettings(config, &hash);
  return hash.hex();
}

double Model::cellSize() const {
  return descriptors_.radii.empty() ? 0.0
                                    : descriptor_config_.cell_ratio * descriptors_.radii.front();
}

namespace {

// The model of `path` from the cache entry of its bytes, or computed (and the entry written). A
// cache file that exists but cannot be used, or cannot be written, is said in `cache_notes`; a
// missing one is the first load. The file is read once: with a cache directory the bytes that
// give the key are the bytes parsed on a miss, so an entry never holds another content's mesh.
ModelLoadResult modelOfFile(const std::string& path,
                            double scale,
                            const std::string& id,
                            const DescriptorConfig& descriptor_config,
                            const std::string& cache_directory,
                            std::vector<std::string>* cache_notes) {
  ModelLoadResult result;
  std::string key;
  io_internal::FileBytes bytes;
  if (!cache_directory.empty() && io_internal::readWholeFile(path, &bytes).ok()) {
    key = modelFileKey(bytes.view(), scale, descriptorSettingsKey(descriptor_config));
  }
  std::string cache_problem;
  if (!key.empty()) {
    ModelCacheRead read = readModelCache(cache_directory, key);
    if (read.entry) {
      result.warnings = read.entry->load_warnings;
      result.model =
          std::make_shared<const Model>(std::move(*read.entry), id, path, descriptor_config);
      return result;
    }
    if (!read.missing) {
      cache_problem = read.status.message;
    }
  }
  // Without a key (no cache directory, or the read failed: loadMesh says why) from the path.
  MeshLoadResult loaded = key.empty() ? loadMesh(path, scale)
                                      : io_internal::loadMeshFromBytes(path, bytes.view(), scale);
  bytes = io_internal::FileBytes{};
  result.warnings = loaded.warnings;
  if (!loaded.status.ok()) {
    result.status = loaded.status;
    return result;
  }
  if (computeBoundingBox(loaded.mesh.vertices).diagonal() <= 0.0) {
    result.status =
        Status::failure(StatusCode::kDegenerateInput, "CAD model '" + path + "' has zero extent");
    return result;
  }
  auto model = std::make_shared<const Model>(std::move(loaded.mesh), id, path, descriptor_config);
  if (!cache_problem.empty()) {
    cache_notes->push_back(cache_problem + ": computed again");
  }
  // Only a usable model is kept: a failed one is computed again, and fails again, next time.
  const bool usable = model->topology().area > 0.0 && model->query().status().ok() &&
                      model->descriptors().status.ok();
  if (!key.empty() && usable) {
    const Status written =
        writeModelCache(cache_directory, key, model->cacheEntry(std::move(loaded.warnings)));
    if (!written.ok()) {
      cache_notes->push_back(written.message + " (the model is used, not cached)");
    }
  }
  result.model = std::move(model);
  return result;
}

}  // namespace

ModelLoadResult loadModel(const std::string& path,
                          double scale,
                          const std::string& id,
                          const DescriptorConfig& descriptor_config,
                          const std::string& cache_directory) {
  std::vector<std::string> cache_notes;
  ModelLoadResult result =
      modelOfFile(path, scale, id, descriptor_config, cache_directory, &cache_notes);
  if (!result.status.ok()) {
    result.model.reset();
    return result;
  }
  const Model& model = *result.model;
  std::vector<std::string> notes;
  if (model.topology().area <= 0.0) {
    result.status = Status::failure(StatusCode::kDegenerateInput,
                                    "CAD model '" + path + "' has zero surface area");
  } else if (!model.query().status().ok()) {
    result.status = model.query().status();
    result.status.message = "CAD model '" + path + "': " + result.status.message;
  } else if (!model.descriptors().status.ok()) {
    result.status = model.descriptors().status;
    result.status.message = "CAD model '" + path + "': " + result.status.message;
  }
  if (!result.status.ok()) {
    result.model.reset();
    return result;
  }
  if (model.orientation().flipped_faces > 0) {
    notes.push_back("CAD model '" + path +
                    "': " + std::to_string(model.orientation().flipped_faces) +
                    " faces were wound inward or inconsistently and were turned to face outward");
  }
  const MeshTopology& topology = model.topology();
  if (!topology.isClosedManifold()) {
    notes.push_back("CAD model '" + path + "' is not a closed, consistently oriented " +
                    "manifold (" + std::to_string(topology.boundary_edges) + " boundary, " +
                    std::to_string(topology.non_manifold_edges) + " non-manifold, " +
                    std::to_string(topology.misoriented_edges) +
                    " misoriented edges): deviation signs may be unreliable");
  }
  result.warnings.insert(result.warnings.end(), notes.begin(), notes.end());
  result.warnings.insert(result.warnings.end(), cache_notes.begin(), cache_notes.end());
  return result;
}

}  // namespace freeform_inspection
