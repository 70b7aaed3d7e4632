// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// libFuzzer target: PLY through loadScan. Corpus: test/data/fuzz/ply_scan/ (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>

#include "fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = freeform_inspection::fuzz;
  fuzz::abortIfBroken(fuzz::fuzzPlyScan(data, size));
  return 0;
}
