// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <charconv>
#include <climits>
#include <cstdint>
#include <exception>
#include <limits>
#include <string>

#include "binary_util.h"
#include "checks.h"
#include "file_util.h"

#include "freeform_inspection/io.h"

namespace freeform_inspection {
namespace {

Status cannotWrite(const std::string& path, const std::string& why) {
  return Status::failure(StatusCode::kInvalidInput, "cannot write '" + path + "': " + why);
}

std::string header(const char* format,
                   std::size_t vertices,
                   const char* type,
                   bool normals,
                   bool face_element,
                   std::size_t faces) {
  std::string text = std::string("ply\nformat ") + format +
                     " 1.0\ncomment freeform_inspection\nelement vertex " +
                     std::to_string(vertices) + "\n";
  for (const char* name : {"x", "y", "z"}) {
    text += std::string("property ") + type + " " + name + "\n";
  }
  if (normals) {
    for (const char* name : {"nx", "ny", "nz"}) {
      text += std::string("property ") + type + " " + name + "\n";
    }
  }
  if (face_element) {
    text += "element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\n";
  }
  return text + "end_header\n";
}

// Shortest text that reads back to the same float / double (locale-independent).
template <typename T>
void appendText(std::string* out, T value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out->append(buffer, result.ptr);
}

template <typename T>
void appendVertex(std::string* out, const Eigen::Vector3d& v, bool binary) {
  for (int i = 0; i < 3; ++i) {
    const auto value = static_cast<T>(v[i]);
    if (binary) {
      io_internal::appendLittleEndian(out, value);
    } else {
      if (i > 0) {
        out->push_back(' ');
      }
      appendText(out, value);
    }
  }
}

template <typename T>
std::string pointBody(const Points& points, const Points& normals, bool binary) {
  std::string body;
  body.reserve(points.size() * (normals.empty() ? 3 : 6) * (binary ? sizeof(T) : 16));
  for (std::size_t i = 0; i < points.size(); ++i) {
    appendVertex<T>(&body, points[i], binary);
    if (!normals.empty()) {
      if (!binary) {
        body.push_back(' ');
      }
      appendVertex<T>(&body, normals[i], binary);
    }
    if (!binary) {
      body.push_back('\n');
    }
  }
  return body;
}

}  // namespace

Status saveMeshPly(const std::string& path, const TriangleMesh& mesh, double scale) {
  try {
    const Status status = io_internal::checkMeshForWriting(path, mesh, scale);
    if (!status.ok()) {
      return status;
    }
    if (mesh.vertices.size() > static_cast<std::size_t>(INT_MAX)) {
      return cannotWrite(path, "too many vertices for int face indices");
    }
    std::string bytes = header(
        "binary_little_endian", mesh.vertices.size(), "float", false, true, mesh.faces.size());
    bytes.reserve(bytes.size() + 12 * mesh.vertices.size() + 13 * mesh.faces.size());
    for (const Eigen::Vector3d& v : mesh.vertices) {
      appendVertex<float>(&bytes, v * scale, true);
    }
    for (const Eigen::Vector3i& f : mesh.faces) {
      io_internal::appendLittleEndian(&bytes, std::uint8_t{3});
      for (int c = 0; c < 3; ++c) {
        io_internal::appendLittleEndian(&bytes, static_cast<std::int32_t>(f[c]));
      }
    }
    return io_internal::writeWholeFile(path, bytes);
  } catch (const std::exception& e) {
    return cannotWrite(path, e.what());
  }
}

Status savePointsPly(const std::string& path,
                     const Points& points,
                     const Points& normals,
                     PlyCoordinateType type,
                     bool binary) {
  try {
    if (!normals.empty() && normals.size() != points.size()) {
      return cannotWrite(path,
                         std::to_string(normals.size()) + " normals for " +
                             std::to_string(points.size()) + " points");
    }
    const bool is_float = type == PlyCoordinateType::kFloat32;
    std::string bytes = header(binary ? "binary_little_endian" : "ascii",
                               points.size(),
                               is_float ? "float" : "double",
                               !normals.empty(),
                               false,
                               0);
    bytes += is_float ? pointBody<float>(points, normals, binary)
                      : pointBody<double>(points, normals, binary);
    return io_internal::writeWholeFile(path, bytes);
  } catch (const std::exception& e) {
    return cannotWrite(path, e.what());
  }
}

}  // namespace freeform_inspection
