// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <climits>
#include <string>
#include <vector>

#include "readers.h"
#include "text_util.h"

namespace freeform_inspection {
namespace io_internal {
namespace {

class ObjParser {
 public:
  explicit ObjParser(const std::string& path) : path_(path) {}

  Status parse(std::string_view bytes, RawGeometry* out) {
    LineReader lines(bytes);
    std::string_view line;
    while (lines.next(&line)) {
      std::size_t pos = 0;
      std::string_view keyword;
      if (!nextToken(line, &pos, &keyword)) {
        continue;
      }
      Status status;
      if (keyword == "v") {
        status = parseVertex(line, pos, lines.lineNumber(), out);
      } else if (keyword == "f") {
        status = parseFace(line, pos, lines.lineNumber(), out);
      }  // vn, vt, g, o, s, usemtl, mtllib, comments, ...: nothing we need
      if (!status.ok()) {
        return status;
      }
    }
    // Positive indices may point forward, so they are checked once all vertices are known.
    if (max_index_ > out->vertices.size()) {
      return invalid(max_index_line_,
                     "vertex index " + std::to_string(max_index_) + " but the file has " +
                         std::to_string(out->vertices.size()) + " vertices");
    }
    out->file_vertices = out->vertices.size();
    if (short_polygons_ > 0) {
      out->warnings.push_back("dropped " + std::to_string(short_polygons_) +
                              " OBJ faces with fewer than 3 vertices");
    }
    return Status::success();
  }

 private:
  Status invalid(std::size_t line_number, const std::string& why) const {
    return Status::failure(StatusCode::kInvalidInput,
                           "'" + path_ + "' line " + std::to_string(line_number) + ": " + why);
  }

  // "v x y z [w]" (some writers append r g b): only x y z are used.
  Status parseVertex(std::string_view line,
                     std::size_t pos,
                     std::size_t line_number,
                     RawGeometry* out) {
    Eigen::Vector3d p;
    std::string_view token;
    for (int i = 0; i < 3; ++i) {
      if (!nextToken(line, &pos, &token) || !parseDouble(token, &p[i])) {
        return invalid(line_number, "expected 'v x y z', got '" + std::string(line) + "'");
      }
    }
    if (out->vertices.size() >= static_cast<std::size_t>(INT_MAX)) {
      return invalid(line_number, "too many vertices");
    }
    out->vertices.push_back(p);
    return Status::success();
  }

  // "f a b c ...", each corner "a", "a/b", "a//c" or "a/b/c"; only the position index counts.
  Status parseFace(std::string_view line,
                   std::size_t pos,
                   std::size_t line_number,
                   RawGeometry* out) {
    polygon_.clear();
    std::string_view token;
    while (nextToken(line, &pos, &token)) {
      const std::string_view position = token.substr(0, token.find('/'));
      long long index = 0;
      if (!parseInteger(position, &index)) {
        return invalid(line_number, "bad face corner '" + std::string(token) + "'");
      }
      const auto defined = static_cast<long long>(out->vertices.size());
      if (index == 0) {
        return invalid(line_number, "vertex index 0 (OBJ indices start at 1)");
      }
      if (index < 0) {
        // Relative: -1 is the last vertex defined so far.
        if (index < -defined) {
          return invalid(line_number,
                         "relative vertex index " + std::to_string(index) + " but only " +
                             std::to_string(defined) + " vertices are defined before it");
        }
        index += defined;
      } else {
        if (index > INT_MAX) {
          return invalid(line_number, "vertex index " + std::to_string(index) + " is too large");
        }
        if (static_cast<std::size_t>(index) > max_index_) {
          max_index_ = static_cast<std::size_t>(index);
          max_index_line_ = line_number;
        }
        index -= 1;
      }
      polygon_.push_back(static_cast<int>(index));
    }
    ++out->file_faces;
    if (polygon_.size() < 3) {
      ++short_polygons_;
      return Status::success();
    }
    for (std::size_t i = 1; i + 1 < polygon_.size(); ++i) {
      out->faces.emplace_back(polygon_[0], polygon_[i], polygon_[i + 1]);
    }
    return Status::success();
  }

  const std::string& path_;
  std::vector<int> polygon_;
  std::size_t max_index_ = 0;
  std::size_t max_index_line_ = 0;
  std::size_t short_polygons_ = 0;
};

}  // namespace

Status readObj(const std::string& path, std::string_view bytes, RawGeometry* out) {
  return ObjParser(path).parse(bytes, out);
}

}  // namespace io_internal
}  // namespace freeform_inspection
