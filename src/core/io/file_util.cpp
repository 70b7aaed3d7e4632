// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "file_util.h"

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>

namespace freeform_inspection {
namespace io_internal {
namespace {

namespace fs = std::filesystem;

using FilePtr = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

// Thread-safe strerror.
std::string osReason(int error) {
  return std::generic_category().message(error);
}

Status cannotOpen(const std::string& path, const std::string& reason) {
  return Status::failure(StatusCode::kInvalidInput, "cannot open '" + path + "': " + reason);
}

Status cannotWrite(const std::string& path, const std::string& reason) {
  return Status::failure(StatusCode::kInvalidInput, "cannot write '" + path + "': " + reason);
}

}  // namespace

Status checkReadableFile(const std::string& path, std::uintmax_t* size) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found) {
    return cannotOpen(path, osReason(ENOENT));
  }
  if (ec) {
    return cannotOpen(path, ec.message());
  }
  if (fs::is_directory(status)) {
    return cannotOpen(path, osReason(EISDIR));
  }
  if (!fs::is_regular_file(status)) {
    return cannotOpen(path, "not a regular file");
  }
  // Opening is the only reliable permission check (ACLs, root, network file systems).
  errno = 0;
  const FilePtr file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) {
    return cannotOpen(path, osReason(errno));
  }
  *size = fs::file_size(path, ec);
  if (ec) {
    return cannotOpen(path, ec.message());
  }
  if (*size == 0) {
    return Status::failure(StatusCode::kInvalidInput, "'" + path + "' is empty (0 bytes)");
  }
  return Status::success();
}

Status readWholeFile(const std::string& path, FileBytes* bytes) {
  std::uintmax_t size = 0;
  Status status = checkReadableFile(path, &size);
  if (!status.ok()) {
    return status;
  }
  errno = 0;
  const FilePtr file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) {
    return cannotOpen(path, osReason(errno));
  }
  bytes->size = static_cast<std::size_t>(size);
  bytes->data.reset(new char[bytes->size]);  // default-initialized: fread fills every byte
  const std::size_t got = std::fread(bytes->data.get(), 1, bytes->size, file.get());
  if (got != bytes->size) {
    return Status::failure(StatusCode::kInvalidInput,
                           "cannot read '" + path + "': got " + std::to_string(got) + " of " +
                               std::to_string(size) + " bytes");
  }
  return Status::success();
}

Status writeWholeFile(const std::string& path, const std::string& bytes) {
  errno = 0;
  std::FILE* raw = std::fopen(path.c_str(), "wb");
  if (raw == nullptr) {
    return cannotWrite(path, osReason(errno));
  }
  const std::size_t written = std::fwrite(bytes.data(), 1, bytes.size(), raw);
  const int write_error = errno;
  // fclose flushes, so a full disk may only show up here.
  const bool closed = std::fclose(raw) == 0;
  if (written != bytes.size()) {
    return cannotWrite(path, osReason(write_error));
  }
  if (!closed) {
    return cannotWrite(path, osReason(errno));
  }
  return Status::success();
}

}  // namespace io_internal
}  // namespace freeform_inspection
