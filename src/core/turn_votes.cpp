// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>

#include "turn_votes_internal.h"
#include <Eigen/Cholesky>

#include "freeform_inspection/global_registration.h"

namespace freeform_inspection {
namespace internal {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;
// Turns closer than this [rad] have the same votes.
constexpr double kSameRotation = 1e-6;

struct Vote {
  std::array<std::int64_t, 3> bin;
  int feature;
  Eigen::Vector3d translation;
};

// The bin (of width `width`, grid offset by `shift` widths) that `translation` falls in.
std::array<std::int64_t, 3> binOf(const Eigen::Vector3d& translation, double width, double shift) {
  const Eigen::Array3d at = (translation.array() / width + shift).floor();
  return {static_cast<std::int64_t>(at.x()),
          static_cast<std::int64_t>(at.y()),
          static_cast<std::int64_t>(at.z())};
}

// The bin with votes from the most distinct features, their count and the mean of their
// translations (one per feature: its first vote there). Sorts `votes`.
std::pair<int, Eigen::Vector3d> densestBin(std::vector<Vote>& votes) {
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

// The translation most distinct features vote for under `rotation`, and their count: one vote
// per feature and bin (its best-ranked candidate there), bins offset by `shift` widths.
std::pair<int, Eigen::Vector3d> featureVotes(const Eigen::Matrix3d& rotation,
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
        votes.push_back({binOf(t, width, shift), feature.feature, t});
      }
    }
  }
  return densestBin(votes);
}

// Two grids of translation bins (the second half a bin off, so that a cluster on a bin's edge is
// not split) over every translation that can lay the sampled scan cells on the sampled CAD cells,
// relative to the turn's centre match: within the sum of the two clouds' radii. Allocated once per
// thread and never cleared: a bin's stamp names the turn and the scan cell that voted there last,
// so that a count left by an earlier turn reads as zero.
struct VoteGrid {
  double width = 0.0;
  double reach = 0.0;  // the translations' bound about the centre match
  std::size_t side = 0;
  std::array<std::vector<int>, 2> stamp;
  std::array<std::vector<int>, 2> count;

  VoteGrid(double bin_width, double radius_sum) : width(bin_width), reach(radius_sum + bin_width) {
    constexpr double kMaxBinsPerSide = 100.0;  // 1M bins: at most 16 MB per thread
    width = std::max(width, 2.0 * reach / kMaxBinsPerSide);
    side = static_cast<std::size_t>(std::ceil(2.0 * reach / width)) + 2;
    for (int g = 0; g < 2; ++g) {
      stamp[static_cast<std::size_t>(g)].assign(side * side * side, 0);
      count[static_cast<std::size_t>(g)].assign(side * side * side, 0);
    }
  }

  // The bin of `offset` (translation minus the centre match) on grid `g`.
  std::size_t binOf(const Eigen::Vector3d& offset, int g) const {
    const Eigen::Array3d at = ((offset.array() + reach) / width + 0.5 * g).floor();
    return (static_cast<std::size_t>(at.z()) * side + static_cast<std::size_t>(at.y())) * side +
           static_cast<std::size_t>(at.x());
  }

  // The bin's centre as an offset.
  Eigen::Vector3d centreOf(std::size_t bin, int g) const {
    const Eigen::Vector3d at(static_cast<double>(bin % side),
                             static_cast<double>((bin / side) % side),
                             static_cast<double>(bin / (side * side)));
    return width * (at + Eigen::Vector3d::Constant(0.5 - 0.5 * g)) -
           Eigen::Vector3d::Constant(reach);
  }
};

// The translation most of the sampled scan cells vote for under `rotation` (turn number `turn`),
// and their count (0 when fewer than `needed` agree): each votes for every sampled CAD cell whose
// normal agrees with its turned one (either sign unless the scan's normals are `oriented`:
// guessed ones may point into the material).
std::pair<int, Eigen::Vector3d> surfaceVotes(const Eigen::Matrix3d& rotation,
                                             int turn,
                                             const std::vector<std::size_t>& scan_cells,
                                             const SurfaceGraph& scan,
                                             const Eigen::Vector3d& scan_centre,
                                             const std::vector<std::size_t>& cad_cells,
                                             const SurfaceGraph& cad,
                                             const Eigen::Vector3d& cad_centre,
                                             bool oriented,
                                             double min_cosine,
                                             int needed,
                                             VoteGrid& grid) {
  constexpr int kFitSteps = 3;
  const double width = grid.width;
  const Eigen::Vector3d centre_match = cad_centre - rotation * scan_centre;
  Points turned(scan_cells.size());
  Points normals(scan_cells.size());
  for (std::size_t k = 0; k < scan_cells.size(); ++k) {
    turned[k] = rotation * scan.centroids[scan_cells[k]];
    normals[k] = rotation * scan.normals[scan_cells[k]];
  }
  const auto agree = [&](std::size_t c, const Eigen::Vector3d& normal) {
    const double cosine = cad.normals[c].dot(normal);
    return (oriented ? cosine : std::abs(cosine)) >= min_cosine;
  };
  const int voters = static_cast<int>(scan_cells.size());
  const int first_stamp = turn * (voters + 1) + 1;  // stamps of this turn: from here on
  int best_count = 0;
  std::size_t best_bin = 0;
  int best_grid = 0;
  for (int k = 0; k < voters; ++k) {
    const auto u = static_cast<std::size_t>(k);
    const int voter = first_stamp + k;
    for (const std::size_t c : cad_cells) {
      if (!agree(c, normals[u])) {
        continue;
      }
      const Eigen::Vector3d offset = cad.centroids[c] - turned[u] - centre_match;
      for (int g = 0; g < 2; ++g) {
        const std::size_t bin = grid.binOf(offset, g);
        int& stamp = grid.stamp[static_cast<std::size_t>(g)][bin];
        int& count = grid.count[static_cast<std::size_t>(g)][bin];
        if (stamp != voter) {
          count = stamp >= first_stamp ? count + 1 : 1;
          stamp = voter;
          if (count > best_count) {
            best_count = count;
            best_bin = bin;
            best_grid = g;
          }
        }
      }
    }
  }
  if (best_count < needed || best_count == 0) {
    return {0, Eigen::Vector3d::Zero()};
  }
  // From the densest bin's centre, a few steps of a translation-only point-to-plane fit: each
  // scan cell paired with its vote nearest the estimate (within a bin's width), the estimate
  // moved along the pairs' normals only. A cell on a wall votes all along the wall, so a mean
  // of its votes would stray along it; the walls across pin those directions down, and a
  // direction none holds stays where the bin put it.
  Eigen::Vector3d estimate = centre_match + grid.centreOf(best_bin, best_grid);
  for (int step = 0; step < kFitSteps; ++step) {
    Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < scan_cells.size(); ++k) {
      double nearest = width * width;
      std::size_t pick = cad_cells.size();
      for (std::size_t i = 0; i < cad_cells.size(); ++i) {
        const std::size_t c = cad_cells[i];
        if (agree(c, normals[k])) {
          const double d2 = (cad.centroids[c] - turned[k] - estimate).squaredNorm();
          if (d2 < nearest) {
            nearest = d2;
            pick = i;
          }
        }
      }
      if (pick < cad_cells.size()) {
        const std::size_t c = cad_cells[pick];
        const Eigen::Matrix3d along = cad.normals[c] * cad.normals[c].transpose();
        normal_matrix += along;
        rhs += along * (cad.centroids[c] - turned[k]);
      }
    }
    // A small pull to the estimate keeps a direction no wall holds where it is.
    const double pull = 1e-3 * std::max(normal_matrix.trace(), 1.0);
    estimate =
        (normal_matrix + pull * Eigen::Matrix3d::Identity()).ldlt().solve(rhs + pull * estimate);
  }
  return {best_count, estimate};
}

// About `count` cells spread evenly over the graph (every n-th), those with a finite normal.
std::vector<std::size_t> spreadCells(const SurfaceGraph& graph, std::size_t count) {
  std::vector<std::size_t> cells;
  const std::size_t stride =
      std::max<std::size_t>(1, graph.size() / std::max<std::size_t>(count, 1));
  for (std::size_t c = 0; c < graph.size() && c < graph.normals.size(); c += stride) {
    if (graph.normals[c].allFinite() && graph.centroids[c].allFinite()) {
      cells.push_back(c);
    }
  }
  return cells;
}

// The best supported starts first, each separate from every better one, at most `max_starts`.
std::vector<Eigen::Isometry3d> bestSeparate(std::vector<std::pair<int, Eigen::Isometry3d>> voted,
                                            const Eigen::Vector3d& reference,
                                            double cell,
                                            std::size_t max_starts) {
  std::stable_sort(
      voted.begin(), voted.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<Eigen::Isometry3d> starts;
  for (const auto& entry : voted) {
    const Eigen::Isometry3d& start = entry.second;
    if (starts.size() < max_starts &&
        std::all_of(starts.begin(), starts.end(), [&](const Eigen::Isometry3d& other) {
          return separatePoses(other, start, reference, cell);
        })) {
      starts.push_back(start);
    }
  }
  return starts;
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
      const auto bin = featureVotes(rotation, candidates, scan, cad, width, shift, votes);
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
  return bestSeparate(std::move(voted), reference, cell, config.max_starts);
}

std::vector<Eigen::Isometry3d> surfaceVotedTurnStarts(const std::vector<Eigen::Isometry3d>& turned,
                                                      const SurfaceGraph& scan,
                                                      const SurfaceGraph& cad,
                                                      bool oriented,
                                                      const Eigen::Vector3d& reference,
                                                      double cell,
                                                      const SurfaceVoteConfig& config) {
  const std::vector<std::size_t> scan_cells = spreadCells(scan, config.scan_cells);
  const std::vector<std::size_t> cad_cells = spreadCells(cad, config.cad_cells);
  if (scan_cells.empty() || cad_cells.empty()) {
    return {};
  }
  const double min_cosine = std::cos(config.normal_tolerance_deg * kDegree);
  // Each cloud's centre and radius: the translations are voted about the centres' match.
  const auto centreAndRadius = [](const SurfaceGraph& graph,
                                  const std::vector<std::size_t>& cells) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const std::size_t c : cells) {
      centre += graph.centroids[c] / static_cast<double>(cells.size());
    }
    double radius = 0.0;
    for (const std::size_t c : cells) {
      radius = std::max(radius, (graph.centroids[c] - centre).norm());
    }
    return std::make_pair(centre, radius);
  };
  const auto [scan_centre, scan_radius] = centreAndRadius(scan, scan_cells);
  const auto [cad_centre, cad_radius] = centreAndRadius(cad, cad_cells);
  const auto needed =
      static_cast<int>(std::ceil(config.min_share * static_cast<double>(scan_cells.size())));
  // A turn with the rotation of an earlier one gets the same votes: voted once.
  std::vector<bool> repeated(turned.size(), false);
  for (std::size_t u = 0; u < turned.size(); ++u) {
    for (std::size_t v = 0; v < u && !repeated[u]; ++v) {
      repeated[u] = Eigen::AngleAxisd(turned[v].linear().transpose() * turned[u].linear()).angle() <
                    kSameRotation;
    }
  }
  // (distinct scan cells, start) per turn, 0 where too few agree; filled in turn order.
  std::vector<std::pair<int, Eigen::Isometry3d>> voted(turned.size());
  const auto count = static_cast<long>(turned.size());
#pragma omp parallel
  {
    VoteGrid grid(config.bin_cells * cell, scan_radius + cad_radius);
#pragma omp for schedule(dynamic, 1)
    for (long i = 0; i < count; ++i) {
      const auto u = static_cast<std::size_t>(i);
      if (repeated[u]) {
        continue;
      }
      const Eigen::Matrix3d rotation = turned[u].linear();
      const auto best = surfaceVotes(rotation,
                                     static_cast<int>(i),
                                     scan_cells,
                                     scan,
                                     scan_centre,
                                     cad_cells,
                                     cad,
                                     cad_centre,
                                     oriented,
                                     min_cosine,
                                     needed,
                                     grid);
      Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
      start.linear() = rotation;
      start.translation() = best.second;
      voted[u] = {best.first, start};
    }
  }
  voted.erase(std::remove_if(
                  voted.begin(), voted.end(), [](const auto& entry) { return entry.first == 0; }),
              voted.end());
  return bestSeparate(std::move(voted), reference, cell, config.max_starts);
}

}  // namespace internal
}  // namespace freeform_inspection
