// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/types.h"

namespace freeform_inspection {

const char* toString(StatusCode code) {
  switch (code) {
    case StatusCode::kOk:
      return "ok";
    case StatusCode::kInvalidInput:
      return "invalid_input";
    case StatusCode::kDegenerateInput:
      return "degenerate_input";
    case StatusCode::kUnitsMismatch:
      return "units_mismatch";
    case StatusCode::kNotConverged:
      return "not_converged";
    case StatusCode::kAmbiguous:
      return "ambiguous";
    case StatusCode::kRegistrationFailed:
      return "registration_failed";
    case StatusCode::kNotImplemented:
      return "not_implemented";
    case StatusCode::kCancelled:
      return "cancelled";
  }
  return "unknown";
}

std::string joinMessages(const std::vector<std::string>& messages) {
  std::string joined;
  for (const auto& message : messages) {
    joined += (joined.empty() ? "" : "; ") + message;
  }
  return joined;
}

}  // namespace freeform_inspection
