// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <cstdint>
#include <exception>
#include <limits>
#include <string>

#include "binary_util.h"
#include "checks.h"
#include "file_util.h"

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

// Deliberately not starting with "solid", which would invite readers to try ascii.
constexpr char kHeaderText[] = "freeform_inspection";
constexpr std::size_t kHeaderBytes = 80;

void appendVector(std::string* out, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) {
    io_internal::appendLittleEndian(out, static_cast<float>(v[i]));
  }
}

}  // namespace

Status saveMeshStl(const std::string& path, const TriangleMesh& mesh, double scale) {
  try {
    const Status status = io_internal::checkMeshForWriting(path, mesh, scale);
    if (!status.ok()) {
      return status;
    }
    if (mesh.faces.size() > std::numeric_limits<std::uint32_t>::max()) {
      return Status::failure(StatusCode::kInvalidInput,
                             "cannot write '" + path + "': too many faces for STL");
    }
    const Points normals = mesh.face_normals.size() == mesh.faces.size()
                               ? mesh.face_normals
                               : computeFaceNormals(mesh.vertices, mesh.faces);
    std::string bytes(kHeaderText);
    bytes.resize(kHeaderBytes, '\0');
    bytes.reserve(kHeaderBytes + 4 + 50 * mesh.faces.size());
    io_internal::appendLittleEndian(&bytes, static_cast<std::uint32_t>(mesh.faces.size()));
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      appendVector(&bytes, normals[f]);
      for (int c = 0; c < 3; ++c) {
        appendVector(&bytes, mesh.vertices[static_cast<std::size_t>(mesh.faces[f][c])] * scale);
      }
      io_internal::appendLittleEndian(&bytes, std::uint16_t{0});  // attribute byte count
    }
    return io_internal::writeWholeFile(path, bytes);
  } catch (const std::exception& e) {
    return Status::failure(StatusCode::kInvalidInput, "cannot write '" + path + "': " + e.what());
  }
}

}  // namespace freeform_inspection
