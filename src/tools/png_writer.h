// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>

#include "rgb_image.h"

namespace freeform_inspection {

/// @brief Encodes an image as PNG (8-bit RGB, no interlace, zlib-deflated rows).
/// @return the file's bytes; empty for an empty image or when zlib fails (out of memory).
std::string encodePng(const RgbImage& image);

}  // namespace freeform_inspection
