// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/config_fields.h"

namespace freeform_inspection {

std::vector<ConfigField> configFields(PipelineConfig& config) {
  return {
      {"input/max_points", &config.input.max_points},
      {"input/min_points", &config.input.min_points},
      {"input/max_extent_ratio", &config.input.max_extent_ratio},
      {"input/min_thickness_ratio", &config.input.min_thickness_ratio},
      {"descriptor/scales", &config.descriptor.scales},
      {"descriptor/max_radius_ratio", &config.descriptor.max_radius_ratio},
      {"descriptor/cell_ratio", &config.descriptor.cell_ratio},
      {"descriptor/cloud_edge_neighbours", &config.descriptor.cloud_edge_neighbours},
      {"descriptor/cloud_neighbours", &config.descriptor.cloud_curvature.neighbours},
      {"descriptor/cloud_thinning_ratio", &config.descriptor.cloud_thinning_ratio},
      {"tolerance/upper", &config.tolerance.upper},
      {"tolerance/lower", &config.tolerance.lower},
  };
}

}  // namespace freeform_inspection
