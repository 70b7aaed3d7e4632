// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/features.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace freeform_inspection {
namespace {

int persistentScales(const FeatureConfig& config, int scales) {
  return config.min_persistent_scales > 0 ? std::min(config.min_persistent_scales, scales)
                                          : (scales + 2) / 3;  // ⌈K/3⌉
}

int longestRun(std::uint32_t bits) {
  int best = 0;
  int run = 0;
  for (; bits != 0U; bits >>= 1U) {
    run = (bits & 1U) != 0U ? run + 1 : 0;
    best = std::max(best, run);
  }
  return best;
}

struct Candidate {
  int cell;
  std::uint32_t rare_scales;
  double rarity;
};

std::vector<Candidate> rareCandidates(const Eigen::MatrixXd& values,
                                      double rare_fraction,
                                      int needed_run) {
  const Eigen::Index n = values.rows();
  std::vector<std::uint32_t> bits(static_cast<std::size_t>(n), 0U);
  std::vector<double> rarity(static_cast<std::size_t>(n), 0.0);
  for (Eigen::Index k = 0; k < values.cols(); ++k) {
    const Eigen::VectorXd column = values.col(k);
    const std::vector<bool> rare = rareAtScale(column, rare_fraction);
    const double mean = column.mean();
    const double sigma = std::sqrt((column.array() - mean).square().mean());
    for (Eigen::Index i = 0; i < n; ++i) {
      if (rare[static_cast<std::size_t>(i)]) {
        bits[static_cast<std::size_t>(i)] |= 1U << static_cast<unsigned>(k);
        rarity[static_cast<std::size_t>(i)] +=
            sigma > 0.0 ? std::abs(column[i] - mean) / sigma : 0.0;
      }
    }
  }
  std::vector<Candidate> candidates;
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    if (longestRun(bits[u]) >= needed_run) {
      candidates.push_back({static_cast<int>(i), bits[u], rarity[u]});
    }
  }
  // Rarest first; the cell index breaks ties so the order never depends on the sort.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.rarity != b.rarity ? a.rarity > b.rarity : a.cell < b.cell;
  });
  return candidates;
}

// Greedy: the rarest candidate of each region, no two closer than `separation`.
std::vector<Candidate> separate(const std::vector<Candidate>& candidates,
                                const Points& positions,
                                double separation,
                                int max_features,
                                const std::function<bool(int)>& eligible,
                                std::vector<signed char>* verdicts) {
  std::vector<Candidate> kept;
  const double separation2 = separation * separation;
  for (const Candidate& candidate : candidates) {
    const Eigen::Vector3d& p = positions[static_cast<std::size_t>(candidate.cell)];
    const bool far = std::all_of(kept.begin(), kept.end(), [&](const Candidate& other) {
      return (positions[static_cast<std::size_t>(other.cell)] - p).squaredNorm() >= separation2;
    });
    if (far && eligible) {  // asked once per cell, however often s is relaxed
      signed char& verdict = (*verdicts)[static_cast<std::size_t>(candidate.cell)];
      if (verdict < 0) {
        verdict = eligible(candidate.cell) ? 1 : 0;
      }
      if (verdict == 0) {
        continue;
      }
    }
    if (far) {
      kept.push_back(candidate);
      if (static_cast<int>(kept.size()) >= max_features) {
        break;
      }
    }
  }
  return kept;
}

}  // namespace

std::vector<std::string> validate(const FeatureConfig& config) {
  std::vector<std::string> errors;
  if (!(config.rare_fraction > 0.0 && config.rare_fraction < 1.0)) {
    errors.push_back("features.rare_fraction must be in (0, 1)");
  }
  if (config.min_persistent_scales < 0) {
    errors.push_back("features.min_persistent_scales must be >= 0 (0: K/3)");
  }
  if (!(config.separation_ratio >= 0.0 && std::isfinite(config.separation_ratio))) {
    errors.push_back("features.separation_ratio must be a finite ratio >= 0");
  }
  if (config.max_features < 3) {
    errors.push_back("features.max_features must be at least 3 (a triplet)");
  }
  if (!(config.min_ball_area >= 0.0 && config.min_ball_area <= 1.0)) {
    errors.push_back("features.min_ball_area must be in [0, 1]");
  }
  if (config.min_features < 3 || config.min_features > config.max_features) {
    errors.push_back("features.min_features must be in [3, features.max_features]");
  }
  return errors;
}

std::vector<bool> rareAtScale(const Eigen::VectorXd& values, double rare_fraction) {
  const auto n = static_cast<std::size_t>(values.size());
  std::vector<bool> rare(n, false);
  if (n == 0) {
    return rare;
  }
  const double mean = values.mean();
  const double sigma = std::sqrt((values.array() - mean).square().mean());           // eq. 13
  const double width = 3.49 * sigma * std::pow(static_cast<double>(n), -1.0 / 3.0);  // eq. 12
  const double low = values.minCoeff();
  if (!(width > 0.0) || !std::isfinite(width)) {
    return rare;  // all values equal: nothing is rare
  }
  const auto bins = static_cast<std::size_t>(std::floor((values.maxCoeff() - low) / width)) + 1;
  std::vector<std::size_t> bin_of(n);
  std::vector<std::size_t> count(bins, 0);
  for (std::size_t i = 0; i < n; ++i) {
    bin_of[i] = std::min(
        bins - 1,
        static_cast<std::size_t>(std::floor((values[static_cast<Eigen::Index>(i)] - low) / width)));
    ++count[bin_of[i]];
  }
  // Least populated first; among equal counts the bin farther from the mean comes first.
  std::vector<std::size_t> order(bins);
  std::iota(order.begin(), order.end(), 0);
  const double mean_bin = (mean - low) / width;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (count[a] != count[b]) {
      return count[a] < count[b];
    }
    const double da = std::abs(static_cast<double>(a) + 0.5 - mean_bin);
    const double db = std::abs(static_cast<double>(b) + 0.5 - mean_bin);
    return da != db ? da > db : a < b;
  });
  const double limit = rare_fraction * static_cast<double>(n);
  std::vector<bool> rare_bin(bins, false);
  std::size_t total = 0;
  for (const std::size_t bin : order) {
    if (static_cast<double>(total + count[bin]) >= limit) {
      break;
    }
    total += count[bin];
    rare_bin[bin] = true;
  }
  for (std::size_t i = 0; i < n; ++i) {
    rare[i] = rare_bin[bin_of[i]];
  }
  return rare;
}

FeatureResult selectFeatures(const Points& positions,
                             const Eigen::MatrixXd& values,
                             double r_max,
                             const FeatureConfig& config,
                             const std::function<bool(int)>& eligible) {
  FeatureResult result;
  if (values.rows() != static_cast<Eigen::Index>(positions.size()) || values.cols() < 1 ||
      values.cols() > 32) {
    result.status = Status::failure(StatusCode::kInvalidInput,
                                    "feature selection needs one descriptor row per position "
                                    "and 1 to 32 scales");
    return result;
  }
  const int needed_run = persistentScales(config, static_cast<int>(values.cols()));
  const double separation = config.separation_ratio * r_max;
  // A part with few distinctive places has fewer rare points than the paper's 2 %: relax s
  // (doubling, at most 8×) until a triplet can be formed with margin, instead of failing.
  std::vector<Candidate> kept;
  std::vector<signed char> verdicts(positions.size(), -1);
  double fraction = config.rare_fraction;
  for (int attempt = 0; attempt < 4; ++attempt, fraction *= 2.0) {
    kept = separate(rareCandidates(values, std::min(fraction, 0.5), needed_run),
                    positions,
                    separation,
                    config.max_features,
                    eligible,
                    &verdicts);
    result.rare_fraction_used = std::min(fraction, 0.5);
    if (static_cast<int>(kept.size()) >= config.min_features) {
      break;
    }
  }
  for (const Candidate& c : kept) {
    result.cells.push_back(c.cell);
    result.rare_scales.push_back(c.rare_scales);
    result.rarity.push_back(c.rarity);
  }
  if (result.cells.size() < 3) {
    result.status = Status::failure(StatusCode::kRegistrationFailed,
                                    "only " + std::to_string(result.cells.size()) +
                                        " rare features found on the scan (3 needed): the "
                                        "scanned surface has too little distinctive shape");
  }
  return result;
}

}  // namespace freeform_inspection
