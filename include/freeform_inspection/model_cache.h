// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "freeform_inspection/chord_error.h"
#include "freeform_inspection/descriptor.h"
#include "freeform_inspection/mesh.h"
#include "freeform_inspection/mesh_orientation.h"
#include "freeform_inspection/symmetry.h"
#include "freeform_inspection/types.h"

/// @file model_cache.h
/// What a Model computes once about its CAD file (the welded, outward-wound mesh with its
/// topology, the descriptors of its refined mesh and its self-symmetries: 0.1 s to read and
/// prepare a fine CAD, 0.3–1 s of descriptors for a part of a few thousand triangles, far more for
/// a fine one), kept in one file per model in a cache directory, under a key of the file's bytes,
/// its unit scale and the descriptor settings (modelFileKey()). The next load of the same file
/// with the same settings (the next CLI run, a node restart, a product changeover through
/// ~load_model) reads the cache file instead of the CAD.
///
/// A file holds the key, this package's version and a checksum of its contents: a file of
/// another model, settings or version, a truncated or damaged one is refused with a reason and
/// the model is computed again (and the file rewritten). Results are bit-identical either way.

namespace freeform_inspection {

/// What the cache keeps of a model.
struct ModelCacheEntry {
  TriangleMesh mesh;                            ///< as the Model holds it: metres, wound outward
  OrientationResult orientation;                ///< what winding it outward changed
  MeshTopology topology;                        ///< of `mesh`
  std::vector<std::uint8_t> face_border_edges;  ///< Model::faceBorderEdges()
  std::vector<std::string> load_warnings;       ///< what reading the file said (loadMesh)
  std::string descriptor_key;                   ///< Model::descriptorKey()
  DescriptorResult descriptors;
  std::vector<Symmetry> symmetries;
  ChordError chord_error;                             ///< Model::chordError()
  double thickness = 0.0;                             ///< Model::thickness()
  std::vector<Eigen::Isometry3d> normal_frame_turns;  ///< Model::normalFrameTurns()
};

/// @brief The key of a CAD file's entry: a hash of its bytes, the unit scale it is loaded with
/// and the descriptor settings (`settings_key`, descriptorSettingsKey()).
std::string modelFileKey(std::string_view file_bytes,
                         double scale,
                         const std::string& settings_key);

/// @brief The package version (package.xml) this library was built as; cache files carry it.
const char* packageVersion();

/// @brief The file of `key` in `directory`.
std::string modelCacheFile(const std::string& directory, const std::string& key);

/// @brief Writes the entry for `key` into `directory` (created when missing): to a temporary
/// file first, then renamed, so that a reader never sees half a file.
/// @return kInvalidInput with the reason when the directory or the file cannot be written.
Status writeModelCache(const std::string& directory,
                       const std::string& key,
                       const ModelCacheEntry& entry);

/// Outcome of a cache read.
struct ModelCacheRead {
  /// ok with `entry`; otherwise kInvalidInput with the reason (no file, or an unusable one)
  Status status;
  bool missing = false;  ///< no file for the key: the first load, not an error
  std::optional<ModelCacheEntry> entry;
};

/// @brief Reads the entry for `key` from `directory`. Never throws; every size in the file is
/// checked against what is left of it before anything is allocated.
ModelCacheRead readModelCache(const std::string& directory, const std::string& key);

}  // namespace freeform_inspection
