// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

// Internal to the core library: which way a cloud's unsigned normals face, from what can be seen
// of the cloud from outside. Used by the cloud curvature to orient PCA normals when the scan
// gives none (docs/descriptors.md, "Orientation from visibility").

#include <vector>

#include "freeform_inspection/types.h"

namespace freeform_inspection {
namespace internal {

/// How a visibility vote is taken.
struct VisibilityConfig {
  int direction_pairs = 32;      ///< antipodal pairs of viewing directions (Fibonacci sphere)
  double pixel = 0.0;            ///< [m] depth-image pixel
  double depth_tolerance = 0.0;  ///< [m] a point this far behind the front-most is still seen
};

/// @brief For every point: +1 when the normal as given faces every direction the point is seen
/// from (at least two, none against), −1 when it faces away from all of them, 0 otherwise.
/// A point of a closed surface is seen only from outside, so its vote is its orientation; a
/// point of an open sheet (a single view) is seen from both sides of each antipodal pair, and
/// the two votes cancel. Orthographic depth images, one per direction; parallel over the
/// directions, the same for any thread count.
std::vector<signed char> visibilityVotes(const Points& points,
                                         const Points& normals,
                                         const VisibilityConfig& config);

}  // namespace internal
}  // namespace freeform_inspection
