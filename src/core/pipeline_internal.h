// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

// Stages of inspect() that follow the registration, shared by pipeline.cpp and
// inspection_stage.cpp. Not installed.

#include <cstddef>
#include <string>
#include <vector>

#include "freeform_inspection/pipeline.h"

namespace freeform_inspection::internal {

/// "0.123 mm": lengths in messages.
std::string formatLength(double metres);

/// Deviation, statistics, shape deviation and defect regions of a registered scan (CAD frame).
/// `point_normals`: empty, or each scan point's outward normal (scan frame), which the deviation
/// measures it along (DeviationConfig::facing_tolerance_deg).
void measurePart(const Model& model,
                 const Scan& scan,
                 const Points& point_normals,
                 const DescriptorResult& descriptors,
                 const PipelineConfig& config,
                 InspectionResult* result);

/// Whether the part has a pose its verdict may be judged at: registered `ok` (and aligned to its
/// datum targets when it has some) or the caller's fixed pose, and not cancelled.
bool judgedPose(const InspectionResult& result);

/// `reason` without a leading "not evaluated: ", to quote it in another verdict's reason.
std::string withoutNotEvaluated(const std::string& reason);

/// The part's verdict and its reason, kept apart from how sure the registration is; then each
/// named region's (judgeRegions()).
void judge(const PipelineConfig& config, InspectionResult* result);

/// The registered pose refitted to the scan points on regions that align (RegionConfig::align;
/// region_fit.cpp): the rest (stock left for a later operation) does not pull it. Nothing when
/// every region aligns; the whole scan's pose, with a warning, when too few points are left.
void fitToAlignedRegions(const Model& model,
                         const Points& scan_points,
                         const Points& point_normals,
                         const PipelineConfig& config,
                         InspectionResult* result);

// Named regions (regions.h), region_verdict.cpp.

/// The deviation the verdict reads: the map's, NaN on regions left out (RegionConfig::evaluate);
/// `excluded` counts the measured points so hidden.
std::vector<float> judgedDeviation(const std::vector<RegionConfig>& regions,
                                   const DeviationMap& map,
                                   std::size_t* excluded);

/// The CAD cells (regionOf() their centroids: `cell_region`) whose coverage counts: all but
/// those of regions left out; empty (all) when no region is left out.
std::vector<bool> evaluatedCells(const std::vector<RegionConfig>& regions,
                                 const std::vector<int>& cell_region);

/// Each named region's statistics, coverage and defect count; verdicts come from judgeRegions().
std::vector<RegionResult> summarizeRegions(const Model& model,
                                           const PipelineConfig& config,
                                           const DeviationMap& map,
                                           const ToleranceBands& bands,
                                           const std::vector<bool>& covered,
                                           const std::vector<int>& cell_region,
                                           const std::vector<DefectRegion>& defects);

/// Each named region's verdict, after the part's (`result->verdict`): a region that fails fails
/// the part; one that falls short of its min_coverage leaves a passed part not evaluated.
void judgeRegions(const PipelineConfig& config, InspectionResult* result);

}  // namespace freeform_inspection::internal
