// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <cstdint>
#include <string>

#include "binary_util.h"
#include "readers.h"
#include "text_util.h"

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace io_internal {
namespace {

constexpr std::size_t kHeaderBytes = 80;
constexpr std::size_t kPrefixBytes = 84;  // header + uint32 triangle count
constexpr std::size_t kTriangleBytes = 50;

Status invalid(std::string message) {
  return Status::failure(StatusCode::kInvalidInput, std::move(message));
}

// Ascii only when the text starts with "solid" and holds no NUL byte: binary STLs often start
// with "solid" too, but their counts and attribute words almost always contain a zero byte.
bool looksAscii(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && isSpace(bytes[i])) {
    ++i;
  }
  return bytes.substr(i, 5) == "solid" && bytes.find('\0') == std::string_view::npos;
}

Status readBinary(std::string_view bytes, std::uint32_t count, Points* corners) {
  corners->reserve(3 * static_cast<std::size_t>(count));
  for (std::size_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + kPrefixBytes + t * kTriangleBytes;
    for (std::size_t c = 0; c < 3; ++c) {
      const char* corner = record + 12 * (c + 1);  // skip the stored normal
      corners->emplace_back(loadScalar<float>(corner, true),
                            loadScalar<float>(corner + 4, true),
                            loadScalar<float>(corner + 8, true));
    }
  }
  return Status::success();
}

Status readAscii(const std::string& path, std::string_view bytes, Points* corners) {
  LineReader lines(bytes);
  std::string_view line;
  while (lines.next(&line)) {
    std::size_t pos = 0;
    std::string_view keyword;
    if (!nextToken(line, &pos, &keyword)) {
      continue;
    }
    const std::string where = "'" + path + "' line " + std::to_string(lines.lineNumber());
    if (keyword == "vertex") {
      Eigen::Vector3d p;
      std::string_view token;
      for (int i = 0; i < 3; ++i) {
        if (!nextToken(line, &pos, &token) || !parseDouble(token, &p[i])) {
          return invalid(where + ": expected 'vertex x y z', got '" + std::string(line) + "'");
        }
      }
      if (nextToken(line, &pos, &token)) {
        return invalid(where + ": extra value '" + std::string(token) + "' after vertex");
      }
      corners->push_back(p);
    } else if (keyword == "facet") {
      if (corners->size() % 3 != 0) {
        return invalid(where + ": previous facet does not have exactly 3 vertices");
      }
    } else if (keyword != "solid" && keyword != "endsolid" && keyword != "outer" &&
               keyword != "endloop" && keyword != "endfacet") {
      return invalid(where + ": unexpected '" + std::string(keyword) + "' in ascii STL");
    }
  }
  if (corners->size() % 3 != 0) {
    return invalid("'" + path + "': ascii STL has " + std::to_string(corners->size()) +
                   " vertices, not a multiple of 3");
  }
  return Status::success();
}

}  // namespace

Status readStl(const std::string& path, std::string_view bytes, RawGeometry* out) {
  Points corners;
  Status status;
  std::uint32_t count = 0;
  bool binary = false;
  // Binary iff the size matches the stored count: the "solid" prefix proves nothing.
  if (bytes.size() >= kPrefixBytes) {
    count = loadScalar<std::uint32_t>(bytes.data() + kHeaderBytes, true);
    binary = kPrefixBytes + kTriangleBytes * std::uint64_t{count} == bytes.size();
  }
  if (binary) {
    status = readBinary(bytes, count, &corners);
  } else if (looksAscii(bytes)) {
    status = readAscii(path, bytes, &corners);
  } else if (bytes.size() < kPrefixBytes) {
    return invalid("'" + path + "' is too short for a binary STL (" + std::to_string(bytes.size()) +
                   " bytes, need at least 84)");
  } else {
    const std::uint64_t expected = kPrefixBytes + kTriangleBytes * std::uint64_t{count};
    return invalid("binary STL '" + path + "' declares " + std::to_string(count) + " triangles (" +
                   std::to_string(expected) + " bytes) but the file has " +
                   std::to_string(bytes.size()) + " bytes");
  }
  if (!status.ok()) {
    return status;
  }
  out->file_vertices = corners.size();
  out->file_faces = corners.size() / 3;
  TriangleMesh mesh = weldTriangleSoup(corners);
  if (mesh.faces.size() < out->file_faces) {
    out->warnings.push_back("dropped " + std::to_string(out->file_faces - mesh.faces.size()) +
                            " STL triangles whose corners coincide");
  }
  out->vertices = std::move(mesh.vertices);
  out->faces = std::move(mesh.faces);
  return Status::success();
}

}  // namespace io_internal
}  // namespace freeform_inspection
