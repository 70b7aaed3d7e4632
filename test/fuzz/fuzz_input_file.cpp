// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "fuzz_input_file.h"

#include <cstdio>
#include <cstdlib>

#include <unistd.h>

namespace freeform_inspection {
namespace fuzz {
namespace {

[[noreturn]] void harnessFailure(const std::string& what) {
  std::fprintf(stderr, "fuzz harness: %s\n", what.c_str());
  std::abort();
}

const std::string& directory() {
  static const std::string chosen = [] {
    const char* env = std::getenv("FREEFORM_FUZZ_TMPDIR");
    if (env != nullptr && *env != '\0') {
      return std::string(env);
    }
    return std::string(access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp");
  }();
  return chosen;
}

}  // namespace

InputFile::InputFile(const std::uint8_t* data, std::size_t size, const std::string& extension)
    : path_(directory() + "/freeform_fuzz_" + std::to_string(getpid()) + extension) {
  std::FILE* file = std::fopen(path_.c_str(), "wb");
  if (file == nullptr) {
    harnessFailure("cannot open " + path_);
  }
  const bool written = size == 0 || std::fwrite(data, 1, size, file) == size;
  if (std::fclose(file) != 0 || !written) {
    harnessFailure("cannot write " + path_);
  }
}

InputFile::~InputFile() {
  std::remove(path_.c_str());
}

}  // namespace fuzz
}  // namespace freeform_inspection
