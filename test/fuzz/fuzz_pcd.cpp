// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// libFuzzer target: PCD (PCL's parser) through loadScan. Corpus: test/data/fuzz/pcd/
// (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>

#include "fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = freeform_inspection::fuzz;
  fuzz::abortIfBroken(fuzz::fuzzPcd(data, size));
  return 0;
}
