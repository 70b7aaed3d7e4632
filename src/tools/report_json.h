// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <nlohmann/json.hpp>

#include "freeform_inspection/pipeline.h"

namespace freeform_inspection {

/// @brief The CLI's JSON report (design.md §5 contract: field names keep their meaning).
nlohmann::ordered_json toJson(const InspectionResult& result);

}  // namespace freeform_inspection
