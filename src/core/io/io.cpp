// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <utility>

#include "checks.h"
#include "file_util.h"
#include "mesh_bytes.h"
#include "readers.h"

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

using io_internal::RawGeometry;

enum class Format { kStl, kPly, kObj, kPcd };

Status invalid(std::string message) {
  return Status::failure(StatusCode::kInvalidInput, std::move(message));
}

std::string lowerExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) {
    return static_cast<char>(std::tolower(c));
  });
  return extension;
}

Status formatOf(const std::string& path, bool allow_pcd, Format* format) {
  const std::string extension = lowerExtension(path);
  if (extension == ".stl") {
    *format = Format::kStl;
  } else if (extension == ".ply") {
    *format = Format::kPly;
  } else if (extension == ".obj") {
    *format = Format::kObj;
  } else if (extension == ".pcd" && allow_pcd) {
    *format = Format::kPcd;
  } else {
    return invalid("unsupported extension '" + extension + "' of '" + path + "' (expected " +
                   (allow_pcd ? ".ply, .pcd, .stl or .obj)" : ".stl, .ply or .obj)"));
  }
  return Status::success();
}

// Parses a file's bytes (any format but PCD, which PCL reads from the path itself) into
// file-unit geometry.
Status parseRaw(const std::string& path, Format format, std::string_view bytes, RawGeometry* raw) {
  switch (format) {
    case Format::kStl:
      return io_internal::readStl(path, bytes, raw);
    case Format::kPly:
      return io_internal::readPly(path, bytes, raw);
    case Format::kObj:
      return io_internal::readObj(path, bytes, raw);
    case Format::kPcd:
      break;
  }
  return invalid("internal error: unhandled format of '" + path + "'");
}

// Reads any format into file-unit geometry, from `bytes` already read when given (not PCD);
// exceptions become a Status here.
Status readRaw(const std::string& path,
               Format format,
               const std::string_view* bytes,
               RawGeometry* raw) {
  try {
    if (bytes != nullptr) {
      return parseRaw(path, format, *bytes, raw);
    }
    if (format == Format::kPcd) {
      std::uintmax_t size = 0;
      const Status status = io_internal::checkReadableFile(path, &size);
      return status.ok() ? io_internal::readPcd(path, size, raw) : status;
    }
    io_internal::FileBytes read;
    const Status status = io_internal::readWholeFile(path, &read);
    return status.ok() ? parseRaw(path, format, read.view(), raw) : status;
  } catch (const std::bad_alloc&) {
    return invalid("out of memory reading '" + path + "'");
  } catch (const std::exception& e) {
    return invalid("cannot read '" + path + "': " + e.what());
  }
}

// Faces with a repeated index have no area and no defined normal; welding or the file made them.
void dropRepeatedIndexFaces(Triangles* faces, std::vector<std::string>* warnings) {
  const auto end = std::remove_if(faces->begin(), faces->end(), [](const Eigen::Vector3i& f) {
    return f[0] == f[1] || f[1] == f[2] || f[0] == f[2];
  });
  const auto dropped = static_cast<std::size_t>(faces->end() - end);
  faces->erase(end, faces->end());
  if (dropped > 0) {
    warnings->push_back("dropped " + std::to_string(dropped) +
                        " faces with a repeated vertex index");
  }
}

// Removes non-finite points (and the faces using them), keeping normals aligned.
std::size_t removeNonFinite(Scan* scan, std::vector<std::string>* warnings) {
  const bool has_normals = scan->normals.size() == scan->points.size();
  std::vector<int> new_index(scan->points.size(), -1);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < scan->points.size(); ++i) {
    if (scan->points[i].allFinite()) {
      new_index[i] = static_cast<int>(kept);
      scan->points[kept] = scan->points[i];
      if (has_normals) {
        scan->normals[kept] = scan->normals[i];
      }
      ++kept;
    }
  }
  const std::size_t removed = scan->points.size() - kept;
  if (removed == 0) {
    return 0;
  }
  scan->points.resize(kept);
  if (has_normals) {
    scan->normals.resize(kept);
  }
  std::size_t faces_kept = 0;
  for (const Eigen::Vector3i& f : scan->faces) {
    const Eigen::Vector3i g(new_index[static_cast<std::size_t>(f[0])],
                            new_index[static_cast<std::size_t>(f[1])],
                            new_index[static_cast<std::size_t>(f[2])]);
    if (g.minCoeff() >= 0) {
      scan->faces[faces_kept++] = g;
    }
  }
  const std::size_t faces_dropped = scan->faces.size() - faces_kept;
  scan->faces.resize(faces_kept);
  warnings->push_back("removed " + std::to_string(removed) + " non-finite points");
  if (faces_dropped > 0) {
    warnings->push_back("dropped " + std::to_string(faces_dropped) +
                        " faces that used non-finite points");
  }
  return removed;
}

// Scan normals must be unit length; unusable ones become zero rather than invent a direction.
// Only those of finite points are reported (an organized grid's NaN holes have no normal).
void normalizeNormals(const Points& points, Points* normals, std::vector<std::string>* warnings) {
  std::size_t unusable = 0;
  for (std::size_t i = 0; i < normals->size(); ++i) {
    Eigen::Vector3d& n = (*normals)[i];
    const double length = n.norm();
    if (std::isfinite(length) && length > 0.0) {
      n /= length;
    } else {
      n.setZero();
      unusable += points[i].allFinite() ? 1 : 0;
    }
  }
  if (unusable > 0) {
    warnings->push_back(std::to_string(unusable) + " normals are zero or non-finite; set to zero");
  }
}

MeshLoadResult loadMeshUnguarded(const std::string& path,
                                 const std::string_view* bytes,
                                 double scale) {
  MeshLoadResult result;
  Format format = Format::kStl;
  result.status = io_internal::checkScale(scale);
  if (result.status.ok()) {
    result.status = formatOf(path, false, &format);
  }
  RawGeometry raw;
  if (result.status.ok()) {
    result.status = readRaw(path, format, bytes, &raw);
  }
  if (!result.status.ok()) {
    return result;
  }
  result.file_vertices = raw.file_vertices;
  result.file_faces = raw.file_faces;
  result.warnings = std::move(raw.warnings);
  dropRepeatedIndexFaces(&raw.faces, &result.warnings);
  if (raw.faces.empty()) {
    result.status = Status::failure(
        StatusCode::kDegenerateInput,
        raw.file_faces == 0 ? "'" + path + "' has no faces: a CAD model must be a triangle mesh"
                            : "'" + path + "' has no usable faces (all " +
                                  std::to_string(raw.file_faces) + " stored faces are degenerate)");
    return result;
  }
  for (std::size_t i = 0; i < raw.vertices.size(); ++i) {
    raw.vertices[i] *= scale;
    if (!raw.vertices[i].allFinite()) {
      result.status =
          invalid("'" + path + "': vertex " + std::to_string(i) +
                  " is not finite after scaling by " + io_internal::formatNumber(scale));
      return result;
    }
  }
  result.mesh.vertices = std::move(raw.vertices);
  result.mesh.faces = std::move(raw.faces);
  result.mesh.face_normals = computeFaceNormals(result.mesh.vertices, result.mesh.faces);
  // Finite but huge coordinates (1e200) overflow the cross product: a NaN normal would poison
  // every later stage (found by fuzz_ply_mesh).
  for (std::size_t f = 0; f < result.mesh.face_normals.size(); ++f) {
    if (!result.mesh.face_normals[f].allFinite()) {
      result.status = invalid("'" + path + "': face " + std::to_string(f) +
                              " has no finite normal: its vertex coordinates are too large "
                              "(check the scale)");
      result.mesh = TriangleMesh{};
      return result;
    }
  }
  return result;
}

ScanLoadResult loadScanUnguarded(const std::string& path, double scale) {
  ScanLoadResult result;
  Format format = Format::kPly;
  result.status = io_internal::checkScale(scale);
  if (result.status.ok()) {
    result.status = formatOf(path, true, &format);
  }
  RawGeometry raw;
  if (result.status.ok()) {
    result.status = readRaw(path, format, nullptr, &raw);
  }
  if (!result.status.ok()) {
    return result;
  }
  result.file_points = raw.file_vertices;
  result.warnings = std::move(raw.warnings);
  dropRepeatedIndexFaces(&raw.faces, &result.warnings);
  Scan& scan = result.scan;
  scan.points = std::move(raw.vertices);
  scan.faces = std::move(raw.faces);
  if (raw.normals.size() == scan.points.size()) {
    scan.normals = std::move(raw.normals);
  }
  for (Eigen::Vector3d& p : scan.points) {
    p *= scale;  // before the finiteness test, so overflow to inf is caught too
  }
  // An organized PCD keeps its grid, NaN holes included: the pipeline triangulates it on the
  // grid and removes (and counts) the non-finite points itself.
  constexpr auto kMaxSide = static_cast<std::size_t>(std::numeric_limits<int>::max());
  const bool organized = raw.height > 1 && raw.width <= kMaxSide && raw.height <= kMaxSide &&
                         raw.width * raw.height == scan.points.size() && scan.faces.empty();
  if (organized) {
    scan.width = static_cast<int>(raw.width);
    scan.height = static_cast<int>(raw.height);
  } else {
    result.non_finite_removed = removeNonFinite(&scan, &result.warnings);
  }
  const bool any_finite = std::any_of(scan.points.begin(),
                                      scan.points.end(),
                                      [](const Eigen::Vector3d& p) { return p.allFinite(); });
  if (!any_finite) {
    result.status = invalid("scan '" + path + "' has no finite points (" +
                            std::to_string(result.file_points) + " stored)");
    return result;
  }
  normalizeNormals(scan.points, &scan.normals, &result.warnings);
  return result;
}

MeshLoadResult loadMeshGuarded(const std::string& path,
                               const std::string_view* bytes,
                               double scale) {
  try {
    return loadMeshUnguarded(path, bytes, scale);
  } catch (const std::exception& e) {
    MeshLoadResult result;
    result.status = invalid("cannot load mesh '" + path + "': " + e.what());
    return result;
  }
}

}  // namespace

MeshLoadResult loadMesh(const std::string& path, double scale) {
  return loadMeshGuarded(path, nullptr, scale);
}

MeshLoadResult io_internal::loadMeshFromBytes(const std::string& path,
                                              std::string_view bytes,
                                              double scale) {
  return loadMeshGuarded(path, &bytes, scale);
}

ScanLoadResult loadScan(const std::string& path, double scale) {
  try {
    return loadScanUnguarded(path, scale);
  } catch (const std::exception& e) {
    ScanLoadResult result;
    result.status = invalid("cannot load scan '" + path + "': " + e.what());
    return result;
  }
}

Status saveTransform(const std::string& path, const Eigen::Matrix4d& matrix) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  for (int r = 0; r < 4 && out; ++r) {
    char line[128];
    std::snprintf(line,
                  sizeof(line),
                  "%.17g %.17g %.17g %.17g\n",
                  matrix(r, 0),
                  matrix(r, 1),
                  matrix(r, 2),
                  matrix(r, 3));
    out << line;
  }
  out.close();
  return out ? Status::success()
             : Status::failure(StatusCode::kInvalidInput, "cannot write '" + path + "'");
}

}  // namespace freeform_inspection
