// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "base64.h"

#include <cstdint>

namespace freeform_inspection {

std::string base64Encode(std::string_view bytes) {
  constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t available = bytes.size() - i;
    std::uint32_t group = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (available > 1) {
      group |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    }
    if (available > 2) {
      group |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 2]));
    }
    // Three bytes become four 6-bit digits; a short last group is padded with '='.
    for (std::size_t digit = 0; digit < 4; ++digit) {
      text.push_back(digit <= available ? kAlphabet[(group >> (18 - 6 * digit)) & 0x3fu] : '=');
    }
  }
  return text;
}

std::string dataUri(std::string_view mime_type, std::string_view bytes) {
  return "data:" + std::string(mime_type) + ";base64," + base64Encode(bytes);
}

}  // namespace freeform_inspection
