// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

/// @file fuzz_outcome.h
/// What one fuzz input did, shared by the core entries (fuzz_entries.h) and the PointCloud2 entry
/// (fuzz_cloud_entry.h), which must not depend on each other's libraries.

namespace freeform_inspection {
namespace fuzz {

/// What one input did.
struct EntryOutcome {
  bool ok = false;      ///< the loader, parser or conversion reported success
  std::string message;  ///< its Status message (a failure must have one)
  std::string broken;   ///< empty unless an invariant of the result was violated: a bug
};

/// Appends `why` to `outcome->broken`; several invariants may fail at once and all are reported.
inline void markBroken(EntryOutcome* outcome, const std::string& why) {
  outcome->broken += (outcome->broken.empty() ? "" : "; ") + why;
}

/// For the fuzz targets: prints and aborts when an outcome breaks an invariant, so that libFuzzer
/// records the input as a crash.
inline void abortIfBroken(const EntryOutcome& outcome) {
  if (!outcome.broken.empty()) {
    std::fprintf(stderr,
                 "invariant violated: %s\n(status message: %s)\n",
                 outcome.broken.c_str(),
                 outcome.message.c_str());
    std::abort();
  }
}

}  // namespace fuzz
}  // namespace freeform_inspection
