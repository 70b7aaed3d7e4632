// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>
#include <vector>

#include "rgb_image.h"
#include <Eigen/Core>

#include "freeform_inspection/deviation_colours.h"
#include "freeform_inspection/types.h"

/// A small software renderer for coloured point clouds: orthographic projection, square splats,
/// a z-buffer and a little depth shading. Enough for a report's pictures without a GPU, a display
/// or VTK's offscreen rendering (docs/reports.md).

namespace freeform_inspection {

/// An orthographic view direction in the points' frame.
struct OrthoView {
  std::string name;  ///< caption, e.g. "front"
  /// Rows: image right, image up, toward the viewer (orthonormal, right-handed).
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
};

/// Image size and look.
struct SplatConfig {
  int width = 480;                   ///< [px]
  int height = 360;                  ///< [px]
  int margin = 10;                   ///< [px] border left free around the points
  Rgb background = {255, 255, 255};  ///< empty pixels
  double depth_shading = 0.3;        ///< farthest points are darkened by this share, nearest not
};

/// @brief Three views of a point set: its largest face from the front and from the back (along
/// the axis of least spread), and an isometric view between its principal axes.
std::vector<OrthoView> principalViews(const Points& points);

/// @brief Renders `points` with one colour each as seen in `view`, scaled to fit the image.
/// The splat size follows the point density, so a scan covers its surface without holes.
/// Non-finite points are skipped.
/// @param colours one per point; a size mismatch gives an empty (background) image.
RgbImage renderSplats(const Points& points,
                      const std::vector<Rgb>& colours,
                      const OrthoView& view,
                      const SplatConfig& config);

}  // namespace freeform_inspection
