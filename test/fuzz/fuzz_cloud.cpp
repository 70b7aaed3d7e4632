// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// libFuzzer target: sensor_msgs/PointCloud2 → cloudToScan(), the node's reader of every scan it
// receives. The bytes are decoded into a message by decodeCloud(). Corpus: test/data/fuzz/cloud/
// (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>

#include "fuzz_cloud_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = freeform_inspection::fuzz;
  fuzz::abortIfBroken(fuzz::fuzzCloud(data, size));
  return 0;
}
