// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

/// @file types.h
/// Basic geometry containers and the status every stage returns.
///
/// Transforms are named T_<to>_<from>: T_cad_scan maps scan coordinates into the CAD frame.
/// All lengths are metres (REP 103) once data has passed through the loaders.

namespace freeform_inspection {

/// Why a stage stopped. Data-dependent failures are reported here, never thrown.
enum class StatusCode {
  kOk = 0,
  kInvalidInput,        ///< empty, non-finite, malformed or unreadable input
  kDegenerateInput,     ///< well-formed but unusable: flat, collinear, zero area, too few points
  kUnitsMismatch,       ///< sizes that differ by the factor of a unit mix-up
  kNotConverged,        ///< an iterative stage ran out of iterations
  kAmbiguous,           ///< several solutions explain the data equally well
  kRegistrationFailed,  ///< no pose explains the scan (too little shape, wrong part)
  kNotImplemented,      ///< the stage exists in the interface but not yet in the code
  kCancelled,           ///< the caller's progress callback asked to stop
};

/// Short stable name of a status code ("ok", "invalid_input", ...), for logs and JSON.
const char* toString(StatusCode code);

/// Messages joined with "; " into one line (for one-line errors that list several causes).
std::string joinMessages(const std::vector<std::string>& messages);

/// The part's verdict (pipeline.h). PASS/FAIL only after a registration that passed its quality
/// gates, or at a pose the caller fixed (inspectAt).
enum class Verdict { kPass, kFail, kNotEvaluated };

/// A status code plus a message that names the offending quantity and its value.
struct Status {
  StatusCode code = StatusCode::kOk;  ///< kOk when the stage succeeded
  std::string message;                ///< human-readable reason; empty when ok

  bool ok() const { return code == StatusCode::kOk; }
  static Status success() { return Status{}; }
  static Status failure(StatusCode code, std::string message) {
    return Status{code, std::move(message)};
  }
};

/// True when the homogeneous transform `T` is rigid and finite: its rotation part orthonormal to
/// `tolerance` (the largest entry of |RᵀR − I|) with determinant +1, its translation finite. A
/// caller's pose is checked with it before it is used (an initial pose, a virtual sensor's).
bool isRigidTransform(const Eigen::Matrix4d& T, double tolerance);

using Points = std::vector<Eigen::Vector3d>;     ///< positions (metres once loaded) or unit vectors
using Triangles = std::vector<Eigen::Vector3i>;  ///< vertex indices, counter-clockwise from outside

/// A triangle mesh; faces index into `vertices` and every index must be in range. STL files are
/// welded on load (each position once); PLY and OBJ keep their vertices as stored.
struct TriangleMesh {
  Points vertices;      ///< metres once loaded (the functions work in any length unit)
  Triangles faces;      ///< counter-clockwise seen from outside the material
  Points face_normals;  ///< unit outward normal per face (zero for degenerate faces)
};

/// A scan: points, with faces when the scanner delivered a mesh, with normals when known.
struct Scan {
  Points points;    ///< [m] (NaN/inf allowed on input: the pipeline removes and counts them)
  Triangles faces;  ///< empty for a point cloud
  Points normals;   ///< empty, or one per point: unit length, or zero where unknown
  int width = 0;    ///< organized scans (range images): columns; 0 when unorganized
  int height = 0;   ///< organized scans: rows (points are row-major, width·height of them)

  /// True when the points form a width × height grid (NaN where nothing was measured).
  bool isOrganized() const {
    return width > 0 && height > 1 &&
           static_cast<std::size_t>(width) * static_cast<std::size_t>(height) == points.size();
  }
};

/// Axis-aligned bounding box.
struct BoundingBox {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Vector3d max = Eigen::Vector3d::Zero();  ///< [m]

  Eigen::Vector3d extent() const { return max - min; }
  double diagonal() const { return extent().norm(); }
};

}  // namespace freeform_inspection
