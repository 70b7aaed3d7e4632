// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>

#include "freeform_inspection/types.h"

namespace freeform_inspection {

/// @brief Replaces the file at `path` with `bytes`.
/// @return kInvalidInput "cannot write <what> '<path>': <OS reason>" when it cannot be opened,
/// written or closed.
Status writeOutputFile(const std::string& path, const std::string& bytes, const std::string& what);

}  // namespace freeform_inspection
