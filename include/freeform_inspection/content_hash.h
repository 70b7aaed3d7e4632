// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <type_traits>

/// @file content_hash.h
/// A 64-bit FNV-1a hash for traceability keys (model, scan file, configuration). Not
/// cryptographic: it tells "same content" from "changed content", it does not resist tampering.

namespace freeform_inspection {

/// Incremental 64-bit FNV-1a over bytes. Feeding the same bytes in the same order gives the same
/// value on every run and platform of the same byte order.
class ContentHash {
 public:
  /// @brief Adds `size` bytes starting at `data`.
  void addBytes(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      hash_ = (hash_ ^ bytes[i]) * kPrime;
    }
  }

  /// @brief Adds the object representation of a trivially copyable value (numbers, enums).
  template <typename T>
  void add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "hash the contents, not the object");
    addBytes(&value, sizeof(T));
  }

  /// @brief Adds the characters of `text` (not its length or a terminator).
  void addText(std::string_view text) { addBytes(text.data(), text.size()); }

  /// @return the hash of everything added so far.
  std::uint64_t value() const { return hash_; }

  /// @return value() as 16 lower-case hex digits.
  std::string hex() const {
    char text[17];
    std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash_));
    return text;
  }

 private:
  static constexpr std::uint64_t kOffsetBasis = 14695981039346656037ull;  // FNV-1a 64-bit
  static constexpr std::uint64_t kPrime = 1099511628211ull;
  std::uint64_t hash_ = kOffsetBasis;
};

}  // namespace freeform_inspection
