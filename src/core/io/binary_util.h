// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <algorithm>
#include <cstring>
#include <string>

/// @file binary_util.h
/// Unaligned loads and stores with explicit byte order, for the binary STL and PLY formats.
/// memcpy keeps them free of alignment and strict-aliasing problems.

namespace freeform_inspection {
namespace io_internal {

constexpr bool kHostIsLittleEndian = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

/// Reads a T stored at `p` in little-endian (true) or big-endian (false) byte order.
template <typename T>
T loadScalar(const char* p, bool little_endian) {
  char buffer[sizeof(T)];
  std::memcpy(buffer, p, sizeof(T));
  if (little_endian != kHostIsLittleEndian) {
    std::reverse(buffer, buffer + sizeof(T));
  }
  T value;
  std::memcpy(&value, buffer, sizeof(T));
  return value;
}

/// Appends `value` to `out` in little-endian byte order.
template <typename T>
void appendLittleEndian(std::string* out, T value) {
  char buffer[sizeof(T)];
  std::memcpy(buffer, &value, sizeof(T));
  if (!kHostIsLittleEndian) {
    std::reverse(buffer, buffer + sizeof(T));
  }
  out->append(buffer, sizeof(T));
}

}  // namespace io_internal
}  // namespace freeform_inspection
