// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstdint>
#include <string>

#include "freeform_inspection/types.h"

/// @file pcd_header.h
/// A strict reading of a PCD header before PCL sees the file. PCL sizes its point buffer from
/// POINTS while it parses, and keeps parsing header lines after DATA, so a lying or redefined
/// header has to be refused here (both found by fuzz_pcd, docs/fuzzing.md).

namespace freeform_inspection {
namespace io_internal {

/// What a PCD header declares.
struct PcdHeader {
  enum class Data { kAscii, kBinary, kBinaryCompressed };

  std::uint64_t points = 0;       ///< POINTS, equal to WIDTH × HEIGHT
  std::uint64_t point_bytes = 0;  ///< sum of SIZE × COUNT over the fields
  std::uint64_t values = 0;       ///< sum of COUNT: numbers per point in ascii
  Data data = Data::kAscii;
  std::uint64_t data_offset = 0;  ///< first byte after the DATA line
  bool has_viewpoint = false;
  std::string viewpoint;  ///< the VIEWPOINT values as written
};

/// @brief Reads the header of `path`: comments and blank lines anywhere, otherwise the keywords
/// of PCD v0.7 in their order, each once (VERSION, COUNT and VIEWPOINT optional, COLUMNS for
/// FIELDS), SIZE 1/2/4/8, TYPE I/U/F, COUNT >= 1, POINTS = WIDTH × HEIGHT, DATA ascii, binary or
/// binary_compressed; and no line after DATA that PCL would take for a header line.
/// @return kInvalidInput "cannot read PCD '<path>': header line N: ..." otherwise.
Status parsePcdHeader(const std::string& path, PcdHeader* header);

/// @brief Refuses a header whose points cannot fit in the `file_size` bytes: ascii needs a
/// character and a separator per value, binary point_bytes per point; binary_compressed must
/// store the uncompressed size the header implies, a compressed size within the file, and no
/// more than LZF's largest expansion (88 times).
Status checkPcdDataSize(const std::string& path, const PcdHeader& header, std::uint64_t file_size);

/// The warning for a VIEWPOINT that is not the identity or not 7 numbers; empty otherwise.
std::string pcdViewpointWarning(const PcdHeader& header);

}  // namespace io_internal
}  // namespace freeform_inspection
