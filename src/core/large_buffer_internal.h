// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

// Internal to the core library: storage for the per-point tables of the cloud stages (the
// neighbour table, the orientation graph, the depth images), megabytes each and written in full
// right after they are made.

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace freeform_inspection {
namespace internal {

/// An allocator for large arrays that are about to be overwritten: `resize` leaves the elements
/// uninitialized (zeroing first would touch every page twice), and from 4 MiB on the block is
/// aligned to, and advised onto, 2 MiB transparent huge pages. A first touch of a 4 KiB page
/// is a page fault, and on the virtual machines robot-cell PCs and CI run on a fault costs
/// microseconds: the neighbour table of a 100k-point scan alone took 25 ms of faults, half of
/// its search time (docs/benchmarks.md). Linux only honours the advice where transparent huge
/// pages are enabled for `madvise` or `always`; elsewhere it is plain aligned memory.
template <typename T>
struct LargeBufferAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = LargeBufferAllocator<U>;
  };
  LargeBufferAllocator() = default;
  template <typename U>
  explicit LargeBufferAllocator(const LargeBufferAllocator<U>& /*other*/) {}

  static constexpr std::size_t kHugePage = std::size_t(2) << 20;
  static constexpr std::size_t kLarge = std::size_t(4) << 20;

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kLarge) {
      return std::allocator<T>::allocate(n);
    }
    const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* block = std::aligned_alloc(kHugePage, rounded);
    if (block == nullptr) {
      throw std::bad_alloc();
    }
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(block, rounded, MADV_HUGEPAGE);  // advice only: failure changes nothing
#endif
    return static_cast<T*>(block);
  }

  void deallocate(T* block, std::size_t n) {
    if (n * sizeof(T) < kLarge) {
      std::allocator<T>::deallocate(block, n);
    } else {
      std::free(block);
    }
  }

  template <typename U, typename... Args>
  void construct(U* at, Args&&... args) {
    if constexpr (sizeof...(Args) == 0) {
      ::new (static_cast<void*>(at)) U;  // default-initialized: no zeroing
    } else {
      ::new (static_cast<void*>(at)) U(std::forward<Args>(args)...);
    }
  }
};

template <typename T, typename U>
bool operator==(const LargeBufferAllocator<T>& /*a*/, const LargeBufferAllocator<U>& /*b*/) {
  return true;
}

template <typename T, typename U>
bool operator!=(const LargeBufferAllocator<T>& /*a*/, const LargeBufferAllocator<U>& /*b*/) {
  return false;
}

/// A vector on LargeBufferAllocator.
template <typename T>
using LargeVector = std::vector<T, LargeBufferAllocator<T>>;

}  // namespace internal
}  // namespace freeform_inspection
