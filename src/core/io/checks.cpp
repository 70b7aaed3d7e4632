// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "checks.h"

#include <charconv>
#include <cmath>

namespace freeform_inspection {
namespace io_internal {

std::string formatNumber(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

Status checkScale(double scale) {
  if (std::isfinite(scale) && scale > 0.0) {
    return Status::success();
  }
  return Status::failure(
      StatusCode::kInvalidInput,
      "scale must be finite and > 0 [m per file unit], got " + formatNumber(scale));
}

Status checkFaceIndices(const std::string& path, const TriangleMesh& mesh) {
  const auto vertex_count = static_cast<long long>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int index = mesh.faces[f][c];
      if (index < 0 || index >= vertex_count) {
        return Status::failure(StatusCode::kInvalidInput,
                               "cannot write '" + path + "': face " + std::to_string(f) +
                                   " references vertex " + std::to_string(index) + " of " +
                                   std::to_string(vertex_count));
      }
    }
  }
  return Status::success();
}

Status checkMeshForWriting(const std::string& path, const TriangleMesh& mesh, double scale) {
  const Status status = checkScale(scale);
  return status.ok() ? checkFaceIndices(path, mesh) : status;
}

}  // namespace io_internal
}  // namespace freeform_inspection
