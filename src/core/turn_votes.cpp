// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <algorithm>
#include <array>
#include <cstdint>
#include <tuple>
#include <utility>

#include "turn_votes_internal.h"

#include "freeform_inspection/global_registration.h"

namespace freeform_inspection {
namespace internal {
namespace {

struct Vote {
  std::array<std::int64_t, 3> bin;
  int feature;
  Eigen::Vector3d translation;
};

// The translation most distinct features vote for under `rotation`, and their count: one vote
// per feature and bin (its best-ranked candidate there), bins offset by `shift` widths.
std::pair<int, Eigen::Vector3d> densestBin(const Eigen::Matrix3d& rotation,
                                           const std::vector<CorrespondenceResult>& candidates,
                                           const SurfaceGraph& scan,
                                           const SurfaceGraph& cad,
                                           double width,
                                           double shift,
                                           std::vector<Vote>& votes) {
  votes.clear();
  for (const CorrespondenceResult& sign : candidates) {
    for (const FeatureCandidates& feature : sign.features) {
      const Eigen::Vector3d turned =
          rotation * scan.centroids[static_cast<std::size_t>(feature.feature)];
      for (const int c : feature.cad) {
        const Eigen::Vector3d t = cad.centroids[static_cast<std::size_t>(c)] - turned;
        const Eigen::Array3d at = (t.array() / width + shift).floor();
        votes.push_back({{static_cast<std::int64_t>(at.x()),
                          static_cast<std::int64_t>(at.y()),
                          static_cast<std::int64_t>(at.z())},
                         feature.feature,
                         t});
      }
    }
  }
  std::stable_sort(votes.begin(), votes.end(), [](const Vote& a, const Vote& b) {
    return std::tie(a.bin, a.feature) < std::tie(b.bin, b.feature);
  });
  std::pair<int, Eigen::Vector3d> best{0, Eigen::Vector3d::Zero()};
  for (std::size_t first = 0; first < votes.size();) {
    std::size_t last = first;
    int count = 0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (; last < votes.size() && votes[last].bin == votes[first].bin; ++last) {
      if (last == first || votes[last].feature != votes[last - 1].feature) {
        ++count;
        sum += votes[last].translation;
      }
    }
    if (count > best.first) {
      best = {count, sum / count};
    }
    first = last;
  }
  return best;
}

}  // namespace

std::vector<Eigen::Isometry3d> votedTurnStarts(const std::vector<Eigen::Isometry3d>& turned,
                                               const std::vector<CorrespondenceResult>& candidates,
                                               const SurfaceGraph& scan,
                                               const SurfaceGraph& cad,
                                               const Eigen::Vector3d& reference,
                                               double cell,
                                               const TurnVoteConfig& config) {
  const double width = config.bin_cells * cell;
  std::vector<std::pair<int, Eigen::Isometry3d>> voted;  // (distinct features, start)
  std::vector<Vote> votes;
  for (const Eigen::Isometry3d& turn : turned) {
    const Eigen::Matrix3d rotation = turn.linear();
    std::pair<int, Eigen::Vector3d> best{0, Eigen::Vector3d::Zero()};
    for (const double shift : {0.0, 0.5}) {
      const auto bin = densestBin(rotation, candidates, scan, cad, width, shift, votes);
      if (bin.first > best.first) {
        best = bin;
      }
    }
    if (best.first >= config.min_features) {
      Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
      start.linear() = rotation;
      start.translation() = best.second;
      voted.emplace_back(best.first, start);
    }
  }
  std::stable_sort(
      voted.begin(), voted.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<Eigen::Isometry3d> starts;
  for (const auto& entry : voted) {
    const Eigen::Isometry3d& start = entry.second;
    if (starts.size() < config.max_starts &&
        std::all_of(starts.begin(), starts.end(), [&](const Eigen::Isometry3d& other) {
          return separatePoses(other, start, reference, cell);
        })) {
      starts.push_back(start);
    }
  }
  return starts;
}

}  // namespace internal
}  // namespace freeform_inspection
