// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

/// @file fuzz_input_file.h
/// The loaders take a path and choose the format by its extension, so each fuzz input is written
/// to a file first: "freeform_fuzz_<pid><extension>", unique among running processes (parallel
/// test runs and fuzzers never share one), on /dev/shm when it is writable to keep disk I/O out of
/// the loop, else /tmp (or FREEFORM_FUZZ_TMPDIR). Removed after each input, so a fuzzer stopped at
/// any point leaves at most one small file behind.

namespace freeform_inspection {
namespace fuzz {

/// One input as a file, for as long as the object lives.
class InputFile {
 public:
  /// Writes `data`; aborts when the file cannot be written (a harness failure, not a finding).
  InputFile(const std::uint8_t* data, std::size_t size, const std::string& extension);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace fuzz
}  // namespace freeform_inspection
