// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

// Internal to the core library: the median the robust estimates share (ICP's σ, the scan's
// noise, neighbourhood reaches). Not installed.

#include <algorithm>
#include <vector>

namespace freeform_inspection {
namespace internal {

/// The upper median (the element at size/2 in sorted order); 0 for no values.
inline double median(std::vector<double> values) {
  if (values.empty()) {
    return 0.0;
  }
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace internal
}  // namespace freeform_inspection
