// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "freeform_inspection/types.h"

/// @file file_util.h
/// Whole-file reads and writes that report failures as a Status with the OS reason.

namespace freeform_inspection {
namespace io_internal {

/// Fails unless `path` is an existing, readable, non-empty regular file; sets `size` [bytes].
Status checkReadableFile(const std::string& path, std::uintmax_t* size);

/// A whole file's bytes, in a buffer that is not zero-filled before the read (for a 48 MB scan
/// that fill was a tenth of its load).
struct FileBytes {
  std::unique_ptr<char[]> data;
  std::size_t size = 0;
  std::string_view view() const { return {data.get(), size}; }
};

/// Reads the whole file into `bytes` after checkReadableFile.
Status readWholeFile(const std::string& path, FileBytes* bytes);

/// Replaces `path` with `bytes`; "cannot write '<path>': <reason>" on failure.
Status writeWholeFile(const std::string& path, const std::string& bytes);

}  // namespace io_internal
}  // namespace freeform_inspection
