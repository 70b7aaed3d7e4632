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
      {"features/rare_fraction", &config.features.rare_fraction},
      {"features/min_persistent_scales", &config.features.min_persistent_scales},
      {"features/separation_ratio", &config.features.separation_ratio},
      {"features/max_features", &config.features.max_features},
      {"features/min_features", &config.features.min_features},
      {"features/min_ball_area", &config.features.min_ball_area},
      {"correspondence/descriptor_tolerance", &config.correspondence.descriptor_tolerance},
      {"correspondence/min_candidates", &config.correspondence.min_candidates},
      {"correspondence/max_candidates", &config.correspondence.max_candidates},
      {"correspondence/separation_cells", &config.correspondence.separation_cells},
      {"registration/pair_tolerance_cells", &config.registration.pair_tolerance_cells},
      {"registration/normal_tolerance_deg", &config.registration.normal_tolerance_deg},
      {"registration/min_side_ratio", &config.registration.min_side_ratio},
      {"registration/max_fits", &config.registration.max_fits},
      {"registration/verified_hypotheses", &config.registration.verified_hypotheses},
      {"registration/verification_points", &config.registration.verification_points},
      {"registration/verification_distance_cells",
       &config.registration.verification_distance_cells},
      {"registration/refined_hypotheses", &config.registration.refined_hypotheses},
      {"registration/ambiguity_ratio", &config.registration.ambiguity_ratio},
      {"registration/min_score", &config.registration.min_score},
      {"registration/min_fitness", &config.registration.min_fitness},
      {"registration/max_residual_ratio", &config.registration.max_residual_ratio},
      {"registration/residual_fitness", &config.registration.residual_fitness},
      {"icp/point_to_plane", &config.icp.point_to_plane},
      {"icp/max_iterations", &config.icp.max_iterations},
      {"icp/convergence", &config.icp.convergence},
      {"icp/sigma_multiple", &config.icp.sigma_multiple},
      {"icp/min_cutoff_ratio", &config.icp.min_cutoff_ratio},
      {"icp/max_cutoff_ratio", &config.icp.max_cutoff_ratio},
      {"icp/max_points", &config.icp.max_points},
      {"tolerance/upper", &config.tolerance.upper},
      {"tolerance/lower", &config.tolerance.lower},
      {"deviation/max_distance_ratio", &config.deviation.max_distance_ratio},
      {"deviation/coverage_distance_cells", &config.deviation.coverage_distance_cells},
      {"deviation/histogram_bins", &config.deviation.histogram_bins},
      {"defects/min_points", &config.defects.min_points},
      {"defects/neighbour_spacings", &config.defects.neighbour_spacings},
      {"verdict/min_in_tolerance_fraction", &config.verdict.min_in_tolerance_fraction},
      {"verdict/min_coverage", &config.verdict.min_coverage},
  };
}

}  // namespace freeform_inspection
