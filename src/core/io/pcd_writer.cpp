// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <charconv>
#include <exception>
#include <string>

#include "binary_util.h"
#include "file_util.h"

#include "freeform_inspection/io.h"

// Written by hand rather than through PCL: the format is a short text header and raw floats, and
// PCL's headers are slow to compile (pcd_reader.cpp is the only file that includes them).

namespace freeform_inspection {
namespace {

Status cannotWrite(const std::string& path, const std::string& why) {
  return Status::failure(StatusCode::kInvalidInput, "cannot write '" + path + "': " + why);
}

std::string header(const Scan& scan, std::size_t width, std::size_t height, bool binary) {
  const bool normals = !scan.normals.empty();
  const std::string fields = normals ? "x y z normal_x normal_y normal_z" : "x y z";
  const std::string per_field = normals ? " 4 4 4 4 4 4" : " 4 4 4";
  const std::string types = normals ? " F F F F F F" : " F F F";
  const std::string counts = normals ? " 1 1 1 1 1 1" : " 1 1 1";
  return "# .PCD v0.7 - Point Cloud Data file format (freeform_inspection)\nVERSION 0.7\nFIELDS " +
         fields + "\nSIZE" + per_field + "\nTYPE" + types + "\nCOUNT" + counts + "\nWIDTH " +
         std::to_string(width) + "\nHEIGHT " + std::to_string(height) +
         "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(width * height) + "\nDATA " +
         (binary ? "binary" : "ascii") + "\n";
}

// float32 values: little-endian raw (PCL's "binary" is the host's order, little-endian on every
// platform it ships for), or the shortest text that reads back to the same float ("nan" for NaN).
void appendVector(std::string* out, const Eigen::Vector3d& v, bool binary) {
  for (int i = 0; i < 3; ++i) {
    const auto value = static_cast<float>(v[i]);
    if (binary) {
      io_internal::appendLittleEndian(out, value);
      continue;
    }
    if (!out->empty() && out->back() != '\n') {
      out->push_back(' ');
    }
    char buffer[32];
    const auto written = std::to_chars(buffer, buffer + sizeof(buffer), value);
    out->append(buffer, written.ptr);
  }
}

}  // namespace

Status saveScanPcd(const std::string& path, const Scan& scan, bool binary) {
  try {
    const std::size_t size = scan.points.size();
    if (!scan.normals.empty() && scan.normals.size() != size) {
      return cannotWrite(
          path,
          std::to_string(scan.normals.size()) + " normals for " + std::to_string(size) + " points");
    }
    std::size_t width = size;
    std::size_t height = 1;
    if (scan.width != 0 || scan.height != 0) {
      if (scan.width <= 0 || scan.height <= 0 ||
          static_cast<std::size_t>(scan.width) * static_cast<std::size_t>(scan.height) != size) {
        return cannotWrite(path,
                           "grid " + std::to_string(scan.width) + " x " +
                               std::to_string(scan.height) + " does not hold the " +
                               std::to_string(size) + " points");
      }
      width = static_cast<std::size_t>(scan.width);
      height = static_cast<std::size_t>(scan.height);
    }
    std::string bytes = header(scan, width, height, binary);
    std::string body;
    body.reserve(size * (scan.normals.empty() ? 3 : 6) * (binary ? 4 : 16));
    for (std::size_t i = 0; i < size; ++i) {
      appendVector(&body, scan.points[i], binary);
      if (!scan.normals.empty()) {
        appendVector(&body, scan.normals[i], binary);
      }
      if (!binary) {
        body.push_back('\n');
      }
    }
    return io_internal::writeWholeFile(path, bytes + body);
  } catch (const std::exception& e) {
    return cannotWrite(path, e.what());
  }
}

}  // namespace freeform_inspection
