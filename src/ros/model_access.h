// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstdint>
#include <string>
#include <vector>

/// Which CAD files a ~load_model request may open: anyone on the ROS graph can call it, so it
/// must not become a way to read arbitrary files or exhaust memory.
namespace freeform_inspection_ros {

/// @brief "" when `path` names a regular file inside one of `allowed_dirs` (after resolving
/// `..`, `.` and symbolic links on both sides) of at most `max_bytes`; otherwise the reason,
/// naming the path. An empty `allowed_dirs` allows nothing.
std::string checkModelAccess(const std::string& path,
                             const std::vector<std::string>& allowed_dirs,
                             std::uintmax_t max_bytes);

}  // namespace freeform_inspection_ros
