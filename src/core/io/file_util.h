// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstdint>
#include <string>

#include "freeform_inspection/types.h"

/// @file file_util.h
/// Whole-file reads and writes that report failures as a Status with the OS reason.

namespace freeform_inspection {
namespace io_internal {

/// Fails unless `path` is an existing, readable, non-empty regular file; sets `size` [bytes].
Status checkReadableFile(const std::string& path, std::uintmax_t* size);

/// Reads the whole file into `bytes` after checkReadableFile.
Status readWholeFile(const std::string& path, std::string* bytes);

/// Replaces `path` with `bytes`; "cannot write '<path>': <reason>" on failure.
Status writeWholeFile(const std::string& path, const std::string& bytes);

}  // namespace io_internal
}  // namespace freeform_inspection
