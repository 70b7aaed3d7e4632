// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "freeform_inspection/types.h"

/// @file io.h
/// Loading CAD meshes and scans from files, and writing meshes and clouds.
///
/// Units are never guessed: every loader multiplies coordinates by an explicit `scale` that
/// turns file units into metres (0.001 for a file in millimetres). Data-dependent failures
/// (missing, empty, truncated, corrupt or faceless files) come back as a Status, never as an
/// exception.

namespace freeform_inspection {

/// Result of loading a CAD mesh.
struct MeshLoadResult {
  Status status;                      ///< kInvalidInput / kDegenerateInput with a reason
  TriangleMesh mesh;                  ///< welded, with face normals, in metres
  std::size_t file_vertices = 0;      ///< vertex (or STL corner) count as stored in the file
  std::size_t file_faces = 0;         ///< face count as stored in the file
  std::vector<std::string> warnings;  ///< non-fatal findings (dropped degenerate faces, ...)
};

/// @brief Loads a CAD mesh: STL (ascii or binary), PLY (ascii or binary, float or double
/// coordinates, triangle or polygon faces, triangulated as fans) or OBJ (v/f, polygons as fans,
/// negative indices allowed).
/// @param path file to read; the format is chosen by the extension (case-insensitive).
/// @param scale [m per file unit] multiplies every coordinate; must be finite and > 0.
/// @return status kInvalidInput for missing, unreadable, truncated or malformed files and for
/// a bad scale, kDegenerateInput for files without any usable face.
MeshLoadResult loadMesh(const std::string& path, double scale);

/// Result of loading a scan.
struct ScanLoadResult {
  Status status;                       ///< kInvalidInput with a reason when nothing usable
  Scan scan;                           ///< metres; faces for meshes; NaN kept only in a grid
  std::size_t file_points = 0;         ///< points as stored in the file (STL: 3 per triangle)
  std::size_t non_finite_removed = 0;  ///< NaN/inf points dropped (faces using them dropped too)
  std::vector<std::string> warnings;   ///< non-fatal findings
};

/// @brief Loads a scan: PLY (ascii or binary, float or double x/y/z, optional nx/ny/nz and
/// faces), PCD (through PCL: ascii, binary, binary_compressed), STL or OBJ (as meshes).
/// Non-finite points are removed and counted, except in an organized PCD (HEIGHT > 1): that keeps
/// its grid, all WIDTH × HEIGHT points in row order with NaN holes (and normals) in place and
/// scan.width / scan.height set; the pipeline removes and counts its non-finite points. PLY has no
/// grid, so a PLY scan is always unorganized.
/// @param path file to read; the format is chosen by the extension (case-insensitive).
/// @param scale [m per file unit] multiplies every coordinate; must be finite and > 0.
/// @return status kInvalidInput for missing, unreadable, malformed or empty files.
ScanLoadResult loadScan(const std::string& path, double scale);

/// @brief Writes a mesh as binary STL, coordinates multiplied by `scale` (1000 writes mm).
/// A non-finite or non-positive scale, or a face index out of range, is kInvalidInput.
Status saveMeshStl(const std::string& path, const TriangleMesh& mesh, double scale = 1.0);

/// @brief Writes a mesh as binary little-endian PLY with float coordinates times `scale`.
Status saveMeshPly(const std::string& path, const TriangleMesh& mesh, double scale = 1.0);

/// Numeric type used for PLY coordinates on output.
enum class PlyCoordinateType { kFloat32, kFloat64 };

/// @brief Writes points (and normals if non-empty, one per point) as a PLY point cloud.
/// @param binary binary little-endian when true, ascii otherwise.
Status savePointsPly(const std::string& path,
                     const Points& points,
                     const Points& normals,
                     PlyCoordinateType type = PlyCoordinateType::kFloat32,
                     bool binary = true);

/// @brief Writes a scan as a PCD v0.7 point cloud: float32 x y z, plus normal_x/y/z when the scan
/// has one normal per point (faces are not written). An organized scan keeps its grid (WIDTH ×
/// HEIGHT, NaN points where nothing was measured); any other is WIDTH = points, HEIGHT = 1.
/// @param binary `DATA binary` (little-endian) when true, `DATA ascii` otherwise.
/// @return kInvalidInput when the normals or the grid do not match the points, or the file
/// cannot be written.
Status saveScanPcd(const std::string& path, const Scan& scan, bool binary = true);

/// @brief Writes a 4×4 transform as text, one row per line, 17 significant digits (the format
/// of data/blade/blade_scan_T_cad_scan.txt and of make_case's truth files).
Status saveTransform(const std::string& path, const Eigen::Matrix4d& matrix);

}  // namespace freeform_inspection
