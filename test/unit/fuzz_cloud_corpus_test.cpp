// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// Replays every file kept under test/data/fuzz/cloud/ (minimized corpus and crash-* reproducers
// of the fuzz_cloud target, docs/fuzzing.md) through the same decoder and cloudToScan() the
// fuzzer ran: each must return, a refusal with a message and no points, a success with
// width · height points.
#include <cstdint>
#include <string>

#include "corpus_files.h"
#include "fuzz_cloud_entry.h"
#include <gtest/gtest.h>

namespace freeform_inspection {
namespace fuzz {
namespace {

TEST(FuzzCloudCorpus, EveryInputReturnsAReasonOrWidthTimesHeightPoints) {
  const std::string directory = std::string(FREEFORM_TEST_DATA_DIR) + "/fuzz/cloud";
  const std::vector<std::string> files = corpusFiles(directory);
  ASSERT_FALSE(files.empty()) << "no corpus in " << directory;
  std::size_t converted = 0;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const std::string bytes = fileBytes(file);
    const EntryOutcome outcome =
        fuzzCloud(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    EXPECT_TRUE(outcome.broken.empty()) << outcome.broken;
    if (!outcome.ok) {
      EXPECT_FALSE(outcome.message.empty());
    }
    converted += outcome.ok ? 1 : 0;
  }
  EXPECT_GT(converted, 0u) << "no input of " << directory << " converts";
}

}  // namespace
}  // namespace fuzz
}  // namespace freeform_inspection
