// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "freeform_inspection/descriptor.h"
#include "freeform_inspection/symmetry.h"
#include "freeform_inspection/types.h"

/// @file model_cache.h
/// What a Model computes once about its CAD (the descriptors of its refined mesh and its
/// self-symmetries: 0.3–1 s for a part of a few thousand triangles, far more for a fine CAD),
/// kept in one file per model in a cache directory, under Model::descriptorKey() (the mesh and
/// the descriptor settings). The next load of the same CAD with the same settings (the next CLI
/// run, a node restart, a product changeover through ~load_model) reads the file instead.
///
/// A file holds the key, this package's version and a checksum of its contents: a file of
/// another model, settings or version, a truncated or damaged one is refused with a reason and
/// the model is computed again (and the file rewritten). Results are bit-identical either way.

namespace freeform_inspection {

/// What the cache keeps of a model.
struct ModelCacheEntry {
  DescriptorResult descriptors;
  std::vector<Symmetry> symmetries;
};

/// @brief The package version (package.xml) this library was built as; cache files carry it.
const char* packageVersion();

/// @brief The file of `key` in `directory`.
std::string modelCacheFile(const std::string& directory, const std::string& key);

/// @brief Writes the entry for `key` into `directory` (created when missing): to a temporary
/// file first, then renamed, so that a reader never sees half a file.
/// @return kInvalidInput with the reason when the directory or the file cannot be written.
Status writeModelCache(const std::string& directory,
                       const std::string& key,
                       const DescriptorResult& descriptors,
                       const std::vector<Symmetry>& symmetries);

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
