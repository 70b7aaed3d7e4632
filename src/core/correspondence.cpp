// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/correspondence.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace freeform_inspection {

std::vector<std::string> validate(const CorrespondenceConfig& config) {
  std::vector<std::string> errors;
  if (!(config.descriptor_tolerance > 0.0 && std::isfinite(config.descriptor_tolerance))) {
    errors.push_back("correspondence.descriptor_tolerance must be a finite value > 0");
  }
  if (config.min_candidates < 1) {
    errors.push_back("correspondence.min_candidates must be at least 1");
  }
  if (config.max_candidates < config.min_candidates) {
    errors.push_back("correspondence.max_candidates must be at least min_candidates");
  }
  if (!(config.separation_cells >= 0.0 && std::isfinite(config.separation_cells))) {
    errors.push_back("correspondence.separation_cells must be a finite value >= 0");
  }
  return errors;
}

CorrespondenceResult findCandidates(const Eigen::MatrixXd& scan_values,
                                    const std::vector<int>& features,
                                    const Eigen::MatrixXd& cad_values,
                                    const Points& cad_positions,
                                    double cell_size,
                                    const CorrespondenceConfig& config) {
  CorrespondenceResult result;
  if (scan_values.cols() != cad_values.cols() ||
      cad_values.rows() != static_cast<Eigen::Index>(cad_positions.size())) {
    result.status = Status::failure(StatusCode::kInvalidInput,
                                    "scan and CAD descriptors have different scales");
    return result;
  }
  const auto cad_count = static_cast<std::size_t>(cad_values.rows());
  const double separation2 = std::pow(config.separation_cells * cell_size, 2);
  std::vector<double> distance(cad_count);
  std::vector<int> order(cad_count);
  for (const int feature : features) {
    const Eigen::RowVectorXd descriptor = scan_values.row(feature);
    for (std::size_t c = 0; c < cad_count; ++c) {
      distance[c] = (cad_values.row(static_cast<Eigen::Index>(c)) - descriptor).cwiseAbs().mean();
    }
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      const auto ua = static_cast<std::size_t>(a);
      const auto ub = static_cast<std::size_t>(b);
      return distance[ua] != distance[ub] ? distance[ua] < distance[ub] : a < b;
    });
    FeatureCandidates entry;
    entry.feature = feature;
    for (const int c : order) {
      const double d = distance[static_cast<std::size_t>(c)];
      const auto taken = static_cast<int>(entry.cad.size());
      if (taken >= config.max_candidates ||
          (d > config.descriptor_tolerance && taken >= config.min_candidates)) {
        break;
      }
      const Eigen::Vector3d& p = cad_positions[static_cast<std::size_t>(c)];
      const bool apart = std::all_of(entry.cad.begin(), entry.cad.end(), [&](int other) {
        return (cad_positions[static_cast<std::size_t>(other)] - p).squaredNorm() >= separation2;
      });
      if (apart) {
        entry.cad.push_back(c);
        entry.descriptor_distance.push_back(d);
      }
    }
    result.candidates += entry.cad.size();
    result.features.push_back(std::move(entry));
  }
  return result;
}

}  // namespace freeform_inspection
