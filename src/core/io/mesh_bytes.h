// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>
#include <string_view>

#include "freeform_inspection/io.h"

/// @file mesh_bytes.h
/// loadMesh() on bytes the caller has already read, so that a model cache keyed by a file's
/// bytes holds the mesh of those same bytes even when the file is replaced between two reads.

namespace freeform_inspection {
namespace io_internal {

/// loadMesh(path, scale) with the file's content given as `bytes` (the format still follows
/// the extension of `path`, which also names the file in messages).
MeshLoadResult loadMeshFromBytes(const std::string& path, std::string_view bytes, double scale);

}  // namespace io_internal
}  // namespace freeform_inspection
