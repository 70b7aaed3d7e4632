// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

// Stages of inspect() that follow the registration, shared by pipeline.cpp and
// inspection_stage.cpp. Not installed.

#include <string>

#include "freeform_inspection/pipeline.h"

namespace freeform_inspection::internal {

/// "0.123 mm": lengths in messages.
std::string formatLength(double metres);

/// Deviation, statistics, shape deviation and defect regions of a registered scan (CAD frame).
void measurePart(const Model& model,
                 const Scan& scan,
                 const DescriptorResult& descriptors,
                 const PipelineConfig& config,
                 InspectionResult* result);

/// The part's verdict and its reason, kept apart from how sure the registration is.
void judge(const PipelineConfig& config, InspectionResult* result);

}  // namespace freeform_inspection::internal
