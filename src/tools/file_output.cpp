// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "file_output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace freeform_inspection {

Status writeOutputFile(const std::string& path, const std::string& bytes, const std::string& what) {
  // stdio rather than ofstream: it reports the OS reason (errno) of a failed open or write.
  const auto failed = [&](int error) {
    return Status::failure(StatusCode::kInvalidInput,
                           "cannot write " + what + " '" + path + "': " + std::strerror(error));
  };
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    return failed(errno);
  }
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
  const int write_error = errno;
  const bool closed = std::fclose(file) == 0;
  if (!written || !closed) {
    return failed(written ? errno : write_error);
  }
  return Status::success();
}

}  // namespace freeform_inspection
