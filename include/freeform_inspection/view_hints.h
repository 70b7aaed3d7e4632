// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include "freeform_inspection/types.h"

/// @file view_hints.h
/// Which way a range image's surface faces. A range image (an organized scan) in its sensor's
/// frame was seen from the origin: every measured surface faces it. When the image's own grid
/// agrees — nearly all of its triangles face the origin, or nearly all face away, once wound
/// consistently — the direction to the origin orients the surface normals. Noisy triangles
/// cannot give the normals themselves (at noise above the pixel spacing their normals are
/// random), but they vote reliably on the side.

namespace freeform_inspection {

/// Orientation hints for a scan's normals.
struct ViewHints {
  /// One unit vector per point pointing out of the material (towards the sensor), or empty
  /// when the scan is not a range image in its sensor's frame.
  Points normals;
  double facing_share = 0.5;  ///< share of grid triangles facing the origin
};

/// @brief Hints for an organized scan triangulated on its grid (`scan.faces` from the grid).
/// Empty unless at least `min_agreement` of the triangles face the origin, or at most
/// 1 − `min_agreement` (the grid wound the other way).
ViewHints rangeImageViewHints(const Scan& scan, double min_agreement = 0.8);

}  // namespace freeform_inspection
