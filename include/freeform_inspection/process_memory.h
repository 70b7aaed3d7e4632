// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

/// @file process_memory.h
/// How a one-shot process that runs the pipeline gets its memory: the CLI. For a main(), never
/// for a library: the settings hold for the whole process. A long-running process (the node, the
/// benchmarks' loops over many scans) reuses its heap from the second scan on by itself; there
/// these settings measured no faster (registration_eval, 8 blade scans a run, within the
/// machine's spread either way), so it keeps glibc's defaults.

namespace freeform_inspection {

/// @brief Keeps the memory the stages free for the next stage and has the kernel back the heap
/// with 2 MB pages. The stages allocate and free tens of MB each (hundreds at 1M points); glibc
/// hands blocks over 128 kB back to the kernel on free, so the next stage faults the same pages
/// in again, and every first touch of a 4 kB page is a fault of its own: about 15 % of a CLI run
/// on a virtual machine. Sets one heap for every thread, keeps freed memory, and reserves the heap
/// in one piece advised for transparent huge pages (as glibc's `glibc.malloc.hugetlb=1` tunable
/// does). Blocks over 32 MB (glibc's ceiling for the threshold) are still mapped and returned, and
/// a heap that outgrows the reserve grows in 4 kB pages. A step that fails leaves glibc's default
/// for it: this never fails. Call it first thing in main(), before any thread starts.
void tuneProcessMemory();

}  // namespace freeform_inspection
