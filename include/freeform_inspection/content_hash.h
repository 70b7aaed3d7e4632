// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>

/// @file content_hash.h
/// A 64-bit XXH3 hash (the xxHash library) for traceability keys (model, scan file,
/// configuration) and the model cache's checksum. Not cryptographic: it tells "same content"
/// from "changed content", it does not resist tampering.

struct XXH3_state_s;

namespace freeform_inspection {

/// Incremental 64-bit XXH3 (seed 0) over bytes: the value `xxhsum -H3` prints for the same
/// bytes, whether they are added at once or in pieces, on every run and platform.
class ContentHash {
 public:
  ContentHash();
  ~ContentHash();
  ContentHash(const ContentHash&) = delete;
  ContentHash& operator=(const ContentHash&) = delete;

  /// @brief Adds `size` bytes starting at `data`.
  void addBytes(const void* data, std::size_t size);

  /// @brief Adds the object representation of a trivially copyable value (numbers, enums).
  template <typename T>
  void add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "hash the contents, not the object");
    addBytes(&value, sizeof(T));
  }

  /// @brief Adds the characters of `text` (not its length or a terminator).
  void addText(std::string_view text) { addBytes(text.data(), text.size()); }

  /// @return the hash of everything added so far.
  std::uint64_t value() const;

  /// @return value() as 16 lower-case hex digits.
  std::string hex() const;

 private:
  struct StateDeleter {
    void operator()(XXH3_state_s* state) const;
  };
  std::unique_ptr<XXH3_state_s, StateDeleter> state_;
};

}  // namespace freeform_inspection
