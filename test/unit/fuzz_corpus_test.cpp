// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// Replays every file kept under test/data/fuzz/<target>/ (the minimized fuzz corpus and the
// crash-* reproducers, docs/fuzzing.md) through the same entry function the libFuzzer target
// calls: each must return, a failure with a message, a success with usable data. Under the
// ASan+UBSan build of scripts/test this also re-checks every fixed crash for memory errors.
#include <cstdint>
#include <string>

#include "corpus_files.h"
#include "fuzz_entries.h"
#include <gtest/gtest.h>

namespace freeform_inspection {
namespace fuzz {
namespace {

class FuzzCorpus : public ::testing::TestWithParam<NamedEntry> {};

TEST_P(FuzzCorpus, EveryInputReturnsAReasonOrUsableData) {
  const std::string directory = std::string(FREEFORM_TEST_DATA_DIR) + "/fuzz/" + GetParam().name;
  const std::vector<std::string> files = corpusFiles(directory);
  ASSERT_FALSE(files.empty()) << "no corpus in " << directory;
  std::size_t loaded = 0;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const std::string bytes = fileBytes(file);
    const EntryOutcome outcome =
        GetParam().entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    EXPECT_TRUE(outcome.broken.empty()) << outcome.broken;
    if (!outcome.ok) {
      EXPECT_FALSE(outcome.message.empty());
    }
    loaded += outcome.ok ? 1 : 0;
  }
  // The seeds are valid files: a corpus where nothing loads would exercise only error paths.
  EXPECT_GT(loaded, 0u) << "no input of " << directory << " loads";
}

INSTANTIATE_TEST_SUITE_P(Targets,
                         FuzzCorpus,
                         ::testing::ValuesIn(coreEntries()),
                         [](const ::testing::TestParamInfo<NamedEntry>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace fuzz
}  // namespace freeform_inspection
