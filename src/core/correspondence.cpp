// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/correspondence.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace freeform_inspection {
namespace {

// Mean absolute difference over the scales from one scan descriptor to every CAD cell's.
std::vector<double> descriptorDistances(const Eigen::RowVectorXd& descriptor,
                                        const Eigen::MatrixXd& cad_values) {
  std::vector<double> distance(static_cast<std::size_t>(cad_values.rows()));
  for (std::size_t c = 0; c < distance.size(); ++c) {
    distance[c] = (cad_values.row(static_cast<Eigen::Index>(c)) - descriptor).cwiseAbs().mean();
  }
  return distance;
}

// Calls `visit` on the cells in order of distance (ties by index) until it returns false. The
// cells within `tolerance` are sorted first and on their own, the rest only if the visit goes
// on past them: almost always it stops inside the tolerance, and a full sort of the CAD's
// cells for every feature was most of this stage's time.
template <typename Visit>
void forEachByAgreement(const std::vector<double>& distance, double tolerance, Visit visit) {
  const auto closer = [&](int a, int b) {
    const auto ua = static_cast<std::size_t>(a);
    const auto ub = static_cast<std::size_t>(b);
    return distance[ua] != distance[ub] ? distance[ua] < distance[ub] : a < b;
  };
  std::vector<int> order(distance.size());
  std::iota(order.begin(), order.end(), 0);
  const auto inside = std::partition(order.begin(), order.end(), [&](int c) {
    return distance[static_cast<std::size_t>(c)] <= tolerance;
  });
  std::sort(order.begin(), inside, closer);
  for (auto it = order.begin(); it != inside; ++it) {
    if (!visit(*it)) {
      return;
    }
  }
  std::sort(inside, order.end(), closer);
  for (auto it = inside; it != order.end(); ++it) {
    if (!visit(*it)) {
      return;
    }
  }
}

}  // namespace

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
  if (config.retry_candidates < 0) {
    errors.push_back("correspondence.retry_candidates must be at least 0");
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
  const double separation2 = std::pow(config.separation_cells * cell_size, 2);
  result.features.resize(features.size());
  const auto feature_count = static_cast<std::ptrdiff_t>(features.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t f = 0; f < feature_count; ++f) {
    FeatureCandidates& entry = result.features[static_cast<std::size_t>(f)];
    entry.feature = features[static_cast<std::size_t>(f)];
    const std::vector<double> distance =
        descriptorDistances(scan_values.row(entry.feature), cad_values);
    // CAD cells in order of agreement, ties by index; each kept unless it lies within the
    // separation of one kept before it.
    const auto take = [&](int c) {
      const double d = distance[static_cast<std::size_t>(c)];
      const auto taken = static_cast<int>(entry.cad.size());
      if (taken >= config.max_candidates ||
          (d > config.descriptor_tolerance && taken >= config.min_candidates)) {
        return false;  // done
      }
      const Eigen::Vector3d& p = cad_positions[static_cast<std::size_t>(c)];
      const bool apart = std::all_of(entry.cad.begin(), entry.cad.end(), [&](int other) {
        return (cad_positions[static_cast<std::size_t>(other)] - p).squaredNorm() >= separation2;
      });
      if (apart) {
        entry.cad.push_back(c);
        entry.descriptor_distance.push_back(d);
      }
      return true;
    };
    forEachByAgreement(distance, config.descriptor_tolerance, take);
  }
  for (const FeatureCandidates& entry : result.features) {
    result.candidates += entry.cad.size();
  }
  return result;
}

}  // namespace freeform_inspection
