// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "freeform_inspection/chord_error.h"
#include "freeform_inspection/descriptor.h"
#include "freeform_inspection/mesh.h"
#include "freeform_inspection/mesh_orientation.h"
#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/model_cache.h"
#include "freeform_inspection/symmetry.h"
#include "freeform_inspection/types.h"

/// @file model.h
/// The CAD model: the mesh and everything computed once about it. Built once, const afterwards,
/// shared between inspections (the node keeps it across scans, the CLI for one run).

namespace freeform_inspection {

/// @brief Metres per file unit for a unit name: "m" → 1, "mm" → 0.001, "in" → 0.0254.
/// @return nothing for any other name (units are never guessed).
std::optional<double> unitScale(const std::string& units);

/// A loaded CAD model and everything computed once about it (descriptors at the kernel radii
/// derived from its size). Immutable once built; share it between inspections.
class Model {
 public:
  /// @brief Takes a mesh already in metres, winds it outward and computes its descriptors and
  /// symmetries. Use loadModel() to read one from a file (and keep it in a cache).
  Model(TriangleMesh mesh,
        std::string id,
        std::string source,
        const DescriptorConfig& descriptor_config = DescriptorConfig());

  /// @brief Takes everything from a cache entry written from cacheEntry() of a Model built with
  /// the same settings: the same model, bit for bit, without computing anything but the
  /// closest-point structure.
  Model(ModelCacheEntry entry,
        std::string id,
        std::string source,
        const DescriptorConfig& descriptor_config);

  /// @brief What the cache keeps of this model; `load_warnings` are what reading its file said.
  ModelCacheEntry cacheEntry(std::vector<std::string> load_warnings) const;

  const TriangleMesh& mesh() const { return mesh_; }
  const BoundingBox& bounds() const { return bounds_; }
  /// How thin the part is [m] (principalThickness() of the mesh, mesh.h).
  double thickness() const { return thickness_; }
  const MeshTopology& topology() const { return topology_; }
  const std::string& id() const { return id_; }
  const std::string& source() const { return source_; }  ///< file it was loaded from
  /// Descriptors of the CAD surface, computed on the mesh refined to the cell size (the original
  /// vertices keep their indices, new ones follow); their radii are the ones to use on every
  /// scan.
  const DescriptorResult& descriptors() const { return descriptors_; }
  /// Hash of the mesh and the descriptor settings: the key under which the descriptors may be
  /// cached (the same file content and configuration give the same key).
  const std::string& descriptorKey() const { return descriptor_key_; }
  /// The descriptor settings the CAD's descriptors were computed with: a scan must use the same.
  const DescriptorConfig& descriptorConfig() const { return descriptor_config_; }
  /// Exact closest-point and ray queries on the CAD triangles (ICP, verification, deviation).
  const MeshQuery& query() const { return *query_; }
  /// Surface-graph cell size [m]: the spatial resolution of the descriptors and of the global
  /// registration's tolerances.
  double cellSize() const;
  /// Motions that map the model (nearly) onto itself, found once (symmetry.h).
  const std::vector<Symmetry>& symmetries() const { return symmetries_; }
  /// normalFrameTurns() of the CAD's surface graph (symmetry.h), computed once on construction:
  /// the turns a retried scan's pose is tried at, which are facts of the part, not of the scan.
  const std::vector<Eigen::Isometry3d>& normalFrameTurns() const { return normal_frame_turns_; }
  /// Per face, a bit per edge (bit e: edge from corner e to corner e+1) set when the edge is on
  /// the border of an open surface; empty for a closed mesh.
  const std::vector<std::uint8_t>& faceBorderEdges() const { return face_border_edges_; }
  /// How far its faces may lie from the curved surface they stand for (chord_error.h),
  /// estimated once on construction.
  const ChordError& chordError() const { return chord_error_; }
  /// How the mesh's winding was made consistent and outward on construction.
  const OrientationResult& orientation() const { return orientation_; }
  /// True when the model came from a cache entry instead of being computed.
  bool fromCache() const { return from_cache_; }

 private:
  OrientationResult orientation_;  // before mesh_: filled while mesh_ is oriented
  TriangleMesh mesh_;
  BoundingBox bounds_;
  double thickness_ = 0.0;
  MeshTopology topology_;
  std::string id_;
  std::string source_;
  DescriptorResult descriptors_;
  std::string descriptor_key_;
  DescriptorConfig descriptor_config_;
  std::unique_ptr<MeshQuery> query_;
  std::vector<Symmetry> symmetries_;
  std::vector<Eigen::Isometry3d> normal_frame_turns_;  // after descriptors_: computed from them
  std::vector<std::uint8_t> face_border_edges_;
  ChordError chord_error_;
  bool from_cache_ = false;
};

/// @brief Hash of the descriptor settings alone: equal keys mean the same descriptors.
std::string descriptorSettingsKey(const DescriptorConfig& config);

/// Result of loading a model.
struct ModelLoadResult {
  Status status;                       ///< not ok: `model` is null
  std::shared_ptr<const Model> model;  ///< the model when status is ok
  std::vector<std::string> warnings;   ///< e.g. open or non-manifold mesh (signs less reliable)
};

/// @brief Loads a CAD file (STL, PLY, OBJ) with an explicit unit scale and checks it is usable:
/// at least one face, a non-zero extent, descriptors computable. Open or non-manifold meshes
/// load with a warning.
/// @param scale [m per file unit], e.g. from unitScale("mm").
/// @param cache_directory where the descriptors and symmetries are kept between loads
/// (model_cache.h); empty: none. A cache that cannot be read or written costs a warning, never
/// the load.
ModelLoadResult loadModel(const std::string& path,
                          double scale,
                          const std::string& id,
                          const DescriptorConfig& descriptor_config = DescriptorConfig(),
                          const std::string& cache_directory = "");

}  // namespace freeform_inspection
