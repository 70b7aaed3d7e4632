// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "model_access.h"

#include <filesystem>
#include <system_error>

namespace freeform_inspection_ros {
namespace {

namespace fs = std::filesystem;

// `inner` lies in `dir` when dir's components are a prefix of inner's.
bool inside(const fs::path& inner, const fs::path& dir) {
  auto i = inner.begin();
  for (auto d = dir.begin(); d != dir.end(); ++d, ++i) {
    if (d->empty()) {
      continue;  // a trailing separator
    }
    if (i == inner.end() || *i != *d) {
      return false;
    }
  }
  return true;
}

}  // namespace

std::string checkModelAccess(const std::string& path,
                             const std::vector<std::string>& allowed_dirs,
                             std::uintmax_t max_bytes) {
  std::error_code ec;
  // canonical() follows every symbolic link, so a link inside an allowed directory that points
  // outside it is judged by where it points.
  const fs::path real = fs::canonical(path, ec);
  if (ec) {
    return "cannot open model '" + path + "': " + ec.message();
  }
  bool allowed = false;
  std::string listed;
  for (const auto& dir : allowed_dirs) {
    listed += (listed.empty() ? "" : ", ") + dir;
    const fs::path real_dir = fs::canonical(dir, ec);
    if (!ec && inside(real, real_dir)) {
      allowed = true;
      break;
    }
  }
  if (!allowed) {
    return "model '" + path + "' (" + real.string() +
           ") is outside the model directories ~model_dirs [" + listed + "]";
  }
  if (!fs::is_regular_file(real, ec)) {
    return "model '" + path + "' is not a regular file";
  }
  const std::uintmax_t size = fs::file_size(real, ec);
  if (ec) {
    return "cannot read the size of model '" + path + "': " + ec.message();
  }
  if (size > max_bytes) {
    return "model '" + path + "' has " + std::to_string(size) +
           " bytes, more than ~max_model_mb (" + std::to_string(max_bytes / (1024 * 1024)) +
           " MiB)";
  }
  return "";
}

}  // namespace freeform_inspection_ros
