// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "freeform_inspection/deviation_colours.h"

namespace freeform_inspection {

/// An 8-bit RGB raster, the renderer's output and the PNG encoder's input.
struct RgbImage {
  int width = 0;                     ///< [px]
  int height = 0;                    ///< [px]
  std::vector<std::uint8_t> pixels;  ///< row-major from the top row, 3 bytes (R, G, B) per pixel

  /// @brief A width × height image filled with `background`.
  static RgbImage filled(int width, int height, const Rgb& background) {
    RgbImage image;
    image.width = width;
    image.height = height;
    image.pixels.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
    for (int i = 0; i < width * height; ++i) {
      image.pixels.insert(image.pixels.end(), background.begin(), background.end());
    }
    return image;
  }

  /// @brief Sets pixel (x, y), y counted from the top; the caller keeps it inside the image.
  void set(int x, int y, const Rgb& colour) {
    const std::size_t offset = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                static_cast<std::size_t>(x)) *
                               3;
    pixels[offset] = colour[0];
    pixels[offset + 1] = colour[1];
    pixels[offset + 2] = colour[2];
  }
};

}  // namespace freeform_inspection
