// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "freeform_inspection/types.h"

/// @file readers.h
/// Private per-format readers behind loadMesh / loadScan. They return geometry in file units;
/// the dispatcher in io.cpp applies the scale, drops degenerate faces and non-finite points, so
/// that every format gets the same treatment.

namespace freeform_inspection {
namespace io_internal {

/// Geometry exactly as a file stores it (file units, not yet scaled or filtered).
struct RawGeometry {
  Points vertices;                    ///< as stored (STL: welded from the triangle corners)
  Triangles faces;                    ///< polygons fan-triangulated; indices within `vertices`
  Points normals;                     ///< one per vertex when the file has them, else empty
  std::size_t file_vertices = 0;      ///< vertex (STL: corner) count as stored
  std::size_t file_faces = 0;         ///< face (polygon) count as stored
  std::size_t width = 0;              ///< organized PCD (HEIGHT > 1): columns; else 0
  std::size_t height = 0;             ///< organized PCD: rows (vertices row-major, NaN kept)
  std::vector<std::string> warnings;  ///< non-fatal findings
};

/// STL, ascii or binary (binary iff size == 84 + 50·count). Corners are welded.
Status readStl(const std::string& path, std::string_view bytes, RawGeometry* out);

/// PLY 1.0, ascii / binary little / big endian, any scalar type, extra elements skipped.
Status readPly(const std::string& path, std::string_view bytes, RawGeometry* out);

/// Wavefront OBJ: `v` and `f` lines only; negative indices resolved, polygons as fans.
Status readObj(const std::string& path, std::string_view bytes, RawGeometry* out);

/// PCD through PCL (ascii, binary, binary_compressed); float or double x/y/z. Sets width and
/// height for an organized cloud (HEIGHT > 1). Loads the PCD module on first use.
/// `file_size` [bytes] as checkReadableFile() found it.
Status readPcd(const std::string& path, std::uintmax_t file_size, RawGeometry* out);

struct PcdHeader;

/// The PCL reader itself, inside the PCD module (pcd_reader.cpp), for a file whose `header`
/// readPcd() has checked.
Status readPcdWithPcl(const std::string& path, const PcdHeader& header, RawGeometry* out);

}  // namespace io_internal
}  // namespace freeform_inspection
