// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "freeform_inspection/types.h"

/// @file ply_header.h
/// The PLY header: format, elements and their (scalar or list) properties.

namespace freeform_inspection {
namespace io_internal {

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

/// Size of a binary PLY scalar [bytes].
std::size_t plyTypeSize(PlyType type);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  ///< scalar type, or item type of a list
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;  ///< type of the list length (lists only)
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;  ///< first byte after the "end_header" line
};

/// Parses the header at the start of `bytes`; kInvalidInput naming the line on any problem.
Status parsePlyHeader(const std::string& path, std::string_view bytes, PlyHeader* header);

}  // namespace io_internal
}  // namespace freeform_inspection
