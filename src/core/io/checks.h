// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>

#include "freeform_inspection/types.h"

/// @file checks.h
/// Argument checks shared by the loaders and writers.

namespace freeform_inspection {
namespace io_internal {

/// Shortest round-trip text of a number, independent of the locale ("0.001", "nan", "-inf").
std::string formatNumber(double value);

/// kInvalidInput unless `scale` is finite and > 0.
Status checkScale(double scale);

/// kInvalidInput unless every face index lies within the vertices (before writing a mesh).
Status checkFaceIndices(const std::string& path, const TriangleMesh& mesh);

/// The checks every mesh writer makes first: a valid scale, then valid face indices.
Status checkMeshForWriting(const std::string& path, const TriangleMesh& mesh, double scale);

}  // namespace io_internal
}  // namespace freeform_inspection
