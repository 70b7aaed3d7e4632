// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_outcome.h"

/// @file fuzz_entries.h
/// One entry per fuzz target of the core (docs/fuzzing.md). The libFuzzer targets in test/fuzz/
/// and the corpus regression test (test/unit/fuzz_corpus_test.cpp) call these same functions, so
/// every file kept under test/data/fuzz/<target>/ replays exactly what the fuzzer ran.

namespace freeform_inspection {
namespace fuzz {

using Entry = EntryOutcome (*)(const std::uint8_t* data, std::size_t size);

/// The bytes as a binary or ascii STL, through loadMesh and loadScan.
EntryOutcome fuzzStl(const std::uint8_t* data, std::size_t size);
/// The bytes as a PLY, through loadMesh.
EntryOutcome fuzzPlyMesh(const std::uint8_t* data, std::size_t size);
/// The bytes as a PLY, through loadScan.
EntryOutcome fuzzPlyScan(const std::uint8_t* data, std::size_t size);
/// The bytes as an OBJ, through loadMesh and loadScan.
EntryOutcome fuzzObj(const std::uint8_t* data, std::size_t size);
/// The bytes as a PCD, through loadScan (PCL parses it).
EntryOutcome fuzzPcd(const std::uint8_t* data, std::size_t size);
/// The bytes as pipeline configuration YAML, through parsePipelineConfig.
EntryOutcome fuzzConfigYaml(const std::uint8_t* data, std::size_t size);

/// A core entry and the name of its target: fuzz_<name>, corpus test/data/fuzz/<name>/.
struct NamedEntry {
  const char* name;
  Entry entry;
};

/// Every core entry above.
const std::vector<NamedEntry>& coreEntries();

}  // namespace fuzz
}  // namespace freeform_inspection
