// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// Named regions after the registration: what each one's points show and its verdict
// (docs/inspection.md, "Regions").
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "pipeline_internal.h"

#include "freeform_inspection/model.h"
#include "freeform_inspection/regions.h"

namespace freeform_inspection::internal {
namespace {

bool leftOut(const std::vector<RegionConfig>& regions, int region) {
  return region >= 0 && !regions[static_cast<std::size_t>(region)].evaluate;
}

// A region's verdict from what its points show, as the part's (judge()) without the
// registration's part: that is the part's to say.
void judgeRegion(const RegionConfig& config,
                 const VerdictConfig& verdict,
                 bool with_uncertainty,
                 RegionResult* region) {
  region->verdict = Verdict::kNotEvaluated;
  if (!config.evaluate) {
    region->verdict_reason = "not evaluated: left out of the verdict (evaluate: false)";
    return;
  }
  if (region->deviation.evaluated == 0) {
    region->verdict_reason = "not evaluated: no scan point lies on it";
    return;
  }
  if (region->deviation.coverage < config.min_coverage) {
    region->verdict_reason = "not evaluated: the scan covers " +
                             std::to_string(region->deviation.coverage) + " of it (min_coverage " +
                             std::to_string(config.min_coverage) + ")";
    return;
  }
  const std::string band = "[" + formatLength(region->tolerance.lower) + ", " +
                           formatLength(region->tolerance.upper) + "]";
  const std::size_t failing = with_uncertainty ? region->defects_beyond_rejection : region->defects;
  if (failing > 0) {
    region->verdict = Verdict::kFail;
    region->verdict_reason = std::to_string(failing) +
                             " defect region(s) outside its tolerance band " + band +
                             (with_uncertainty ? " widened by the measurement uncertainty" : "");
    return;
  }
  if (region->deviation.in_tolerance_fraction < verdict.min_in_tolerance_fraction) {
    region->verdict = Verdict::kFail;
    region->verdict_reason = "only " + std::to_string(region->deviation.in_tolerance_fraction) +
                             " of its points lie inside its tolerance band " + band +
                             " (verdict.min_in_tolerance_fraction)";
    return;
  }
  if (with_uncertainty && region->defects_outside_acceptance > 0) {
    region->verdict_reason =
        "not evaluated: " + std::to_string(region->defects_outside_acceptance) +
        " defect region(s) outside its band narrowed by the measurement "
        "uncertainty, none beyond it widened (ISO 14253-1)";
    return;
  }
  region->verdict = Verdict::kPass;
  region->verdict_reason = "inside its tolerance band " + band + ": " +
                           std::to_string(region->deviation.in_tolerance_fraction) + " of " +
                           std::to_string(region->deviation.evaluated) + " points, deviation " +
                           formatLength(region->deviation.min) + " to " +
                           formatLength(region->deviation.max);
}

}  // namespace

std::vector<float> judgedDeviation(const std::vector<RegionConfig>& regions,
                                   const DeviationMap& map,
                                   std::size_t* excluded) {
  std::vector<float> judged = map.deviation;
  *excluded = 0;
  for (std::size_t i = 0; i < map.region.size(); ++i) {
    if (leftOut(regions, map.region[i]) && std::isfinite(judged[i])) {
      judged[i] = std::numeric_limits<float>::quiet_NaN();
      ++*excluded;
    }
  }
  return judged;
}

std::vector<bool> evaluatedCells(const std::vector<RegionConfig>& regions,
                                 const std::vector<int>& cell_region) {
  std::vector<bool> counted(cell_region.size(), true);
  bool any_left_out = false;
  for (std::size_t c = 0; c < cell_region.size(); ++c) {
    if (leftOut(regions, cell_region[c])) {
      counted[c] = false;
      any_left_out = true;
    }
  }
  return any_left_out ? counted : std::vector<bool>();
}

std::vector<RegionResult> summarizeRegions(const Model& model,
                                           const PipelineConfig& config,
                                           const DeviationMap& map,
                                           const ToleranceBands& bands,
                                           const std::vector<bool>& covered,
                                           const std::vector<int>& cell_region,
                                           const std::vector<DefectRegion>& defects) {
  std::vector<RegionResult> results;
  for (std::size_t r = 0; r < config.regions.size(); ++r) {
    const RegionConfig& region = config.regions[r];
    const int index = static_cast<int>(r);
    RegionResult result;
    result.name = region.name;
    result.evaluated = region.evaluate;
    result.tolerance = bands.region_bands[r];
    // Its own points alone (a region left out shows what was measured there, judged nowhere).
    std::vector<float> own(map.size(), std::numeric_limits<float>::quiet_NaN());
    std::size_t others = 0;
    for (std::size_t i = 0; i < map.size(); ++i) {
      if (map.region[i] == index) {
        own[i] = map.deviation[i];
      } else {
        ++others;
      }
    }
    result.deviation =
        summarizeDeviation(own, ToleranceBands(result.tolerance), config.deviation.histogram_bins);
    result.deviation.unmatched -= others;
    std::vector<bool> in_region(cell_region.size());
    for (std::size_t c = 0; c < cell_region.size(); ++c) {
      in_region[c] = cell_region[c] == index;
    }
    result.deviation.coverage = coveredShare(model, covered, in_region);
    for (const DefectRegion& defect : defects) {
      result.defects += defect.region == index ? 1 : 0;
    }
    results.push_back(std::move(result));
  }
  return results;
}

void judgeRegions(const PipelineConfig& config, InspectionResult* result) {
  const bool posed = judgedPose(*result);
  const bool with_uncertainty = result->conformance.measurement_uncertainty > 0.0;
  const RegionResult* failed = nullptr;
  const RegionResult* uncovered = nullptr;
  for (std::size_t r = 0; r < result->regions.size(); ++r) {
    RegionResult& region = result->regions[r];
    const RegionConfig& region_config = config.regions[r];
    if (!posed) {
      region.verdict = Verdict::kNotEvaluated;
      region.verdict_reason = "not evaluated: the part is not (" + result->verdict_reason + ")";
      continue;
    }
    judgeRegion(region_config, config.verdict, with_uncertainty, &region);
    if (region.verdict == Verdict::kFail && failed == nullptr) {
      failed = &region;
    }
    if (region_config.evaluate && region.deviation.coverage < region_config.min_coverage &&
        uncovered == nullptr) {
      uncovered = &region;
    }
  }
  if (!posed) {
    return;
  }
  // A region that fails fails the part; one the scan does not cover as asked leaves a part that
  // would pass not evaluated: an unscanned surface is not a pass.
  if (failed != nullptr && result->verdict != Verdict::kFail) {
    result->verdict = Verdict::kFail;
    result->verdict_reason = "region '" + failed->name + "' fails: " + failed->verdict_reason;
  } else if (uncovered != nullptr && result->verdict == Verdict::kPass) {
    result->verdict = Verdict::kNotEvaluated;
    result->verdict_reason = "not evaluated: region '" + uncovered->name +
                             "': " + withoutNotEvaluated(uncovered->verdict_reason);
  }
}

}  // namespace freeform_inspection::internal
