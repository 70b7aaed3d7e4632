// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/content_hash.h"

#include <cstdio>
#include <new>

#include <xxhash.h>

namespace freeform_inspection {

ContentHash::ContentHash() : state_(XXH3_createState()) {
  if (!state_) {
    throw std::bad_alloc();
  }
  XXH3_64bits_reset(state_.get());
}

ContentHash::~ContentHash() = default;

void ContentHash::StateDeleter::operator()(XXH3_state_s* state) const {
  XXH3_freeState(state);
}

void ContentHash::addBytes(const void* data, std::size_t size) {
  if (size > 0) {
    XXH3_64bits_update(state_.get(), data, size);
  }
}

std::uint64_t ContentHash::value() const {
  return XXH3_64bits_digest(state_.get());
}

std::string ContentHash::hex() const {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(value()));
  return text;
}

}  // namespace freeform_inspection
