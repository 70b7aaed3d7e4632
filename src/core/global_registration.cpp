// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/global_registration.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include <Eigen/Geometry>

namespace freeform_inspection {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

struct Oriented {
  Eigen::Vector3d point;
  Eigen::Vector3d normal;  // unit, or zero when unknown
};

Oriented cellOf(const SurfaceGraph& graph, int cell) {
  const auto c = static_cast<std::size_t>(cell);
  return {graph.centroids[c], graph.normals[c]};
}

// Angle between the lines of two unit vectors, in [0, π/2]. Cloud normals are oriented by
// propagation, which can leave a region flipped; comparing lines keeps the checks valid there.
double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::min(1.0, std::abs(a.dot(b))));
}

bool hasNormal(const Eigen::Vector3d& n) {
  return n.squaredNorm() > 0.5;
}

// The triangle check of §3.5 for one side of a triangle, plus the three angles a pair of
// oriented points keeps under any rigid motion (normal–normal and each normal with the side).
struct PairCheck {
  double distance_tolerance;
  double angle_tolerance;

  bool operator()(const Oriented& s1,
                  const Oriented& s2,
                  const Oriented& c1,
                  const Oriented& c2) const {
    const Eigen::Vector3d ds = s2.point - s1.point;
    const Eigen::Vector3d dc = c2.point - c1.point;
    const double ls = ds.norm();
    const double lc = dc.norm();
    if (std::abs(ls - lc) > distance_tolerance) {
      return false;
    }
    if (!hasNormal(s1.normal) || !hasNormal(s2.normal) || !hasNormal(c1.normal) ||
        !hasNormal(c2.normal) || ls <= 0.0 || lc <= 0.0) {
      return true;
    }
    const Eigen::Vector3d us = ds / ls;
    const Eigen::Vector3d uc = dc / lc;
    return std::abs(angleBetween(s1.normal, s2.normal) - angleBetween(c1.normal, c2.normal)) <=
               angle_tolerance &&
           std::abs(angleBetween(s1.normal, us) - angleBetween(c1.normal, uc)) <= angle_tolerance &&
           std::abs(angleBetween(s2.normal, us) - angleBetween(c2.normal, uc)) <= angle_tolerance;
  }
};

// Consistent candidate pairs of every feature pair: consistent[i][j][a * |C_j| + b].
using PairTable = std::vector<std::vector<std::vector<char>>>;

struct Fit {
  PoseHypothesis pose;
  double rarity_rank;  // sum of the triplet's feature indices: lower = rarer features
};

Eigen::Isometry3d rigidFit(const Eigen::Matrix3d& scan, const Eigen::Matrix3d& cad) {
  Eigen::Isometry3d T;
  T.matrix() = Eigen::umeyama(scan, cad, false);
  return T;
}

// eq. 14, robust reading: each feature counts the squared distance to the nearest of its
// candidates after the motion, truncated at the pair tolerance (a feature without a true match
// must not dominate), averaged over the features.
void scoreByFeatures(const SurfaceGraph& scan,
                     const SurfaceGraph& cad,
                     const CorrespondenceResult& candidates,
                     double tolerance,
                     PoseHypothesis* pose) {
  const double tolerance2 = tolerance * tolerance;
  double sum = 0.0;
  int explained = 0;
  for (const auto& feature : candidates.features) {
    const Eigen::Vector3d p =
        pose->T_cad_scan * scan.centroids[static_cast<std::size_t>(feature.feature)];
    double best = tolerance2;
    for (const int c : feature.cad) {
      best = std::min(best, (cad.centroids[static_cast<std::size_t>(c)] - p).squaredNorm());
    }
    explained += best < tolerance2 ? 1 : 0;
    sum += best;
  }
  pose->features_explained = explained;
  pose->error = sum / static_cast<double>(std::max<std::size_t>(1, candidates.features.size()));
}

bool betterFit(const Fit& a, const Fit& b) {
  if (a.pose.features_explained != b.pose.features_explained) {
    return a.pose.features_explained > b.pose.features_explained;
  }
  if (a.pose.error != b.pose.error) {
    return a.pose.error < b.pose.error;
  }
  return a.rarity_rank < b.rarity_rank;
}

// A consistent triplet: three scan features and one CAD candidate of each.
struct Triplet {
  int feature[3];
  int cad[3];
};

// Every triplet whose three sides pass the pair check, rarest features first, up to `max_fits`
// (serial and cheap: only table lookups and the collinearity test).
std::vector<Triplet> enumerateTriplets(const SurfaceGraph& scan,
                                       const std::vector<FeatureCandidates>& features,
                                       const PairTable& consistent,
                                       double min_side,
                                       std::size_t max_fits) {
  std::vector<Triplet> triplets;
  const std::size_t f_count = features.size();
  for (std::size_t i = 0; i < f_count && triplets.size() < max_fits; ++i) {
    for (std::size_t j = i + 1; j < f_count && triplets.size() < max_fits; ++j) {
      if (consistent[i][j].empty()) {
        continue;
      }
      for (std::size_t k = j + 1; k < f_count && triplets.size() < max_fits; ++k) {
        if (consistent[i][k].empty() || consistent[j][k].empty()) {
          continue;
        }
        const Eigen::Vector3d s0 = cellOf(scan, features[i].feature).point;
        const Eigen::Vector3d s1 = cellOf(scan, features[j].feature).point;
        const Eigen::Vector3d s2 = cellOf(scan, features[k].feature).point;
        const double doubled_area = (s1 - s0).cross(s2 - s0).norm();
        const double longest = std::max({(s1 - s0).norm(), (s2 - s0).norm(), (s2 - s1).norm()});
        if (doubled_area / longest < 0.5 * min_side) {
          continue;  // nearly collinear: the rotation about the line is undetermined
        }
        const std::size_t nj = features[j].cad.size();
        const std::size_t nk = features[k].cad.size();
        for (std::size_t a = 0; a < features[i].cad.size(); ++a) {
          for (std::size_t b = 0; b < nj; ++b) {
            if (consistent[i][j][a * nj + b] == 0) {
              continue;
            }
            for (std::size_t c = 0; c < nk && triplets.size() < max_fits; ++c) {
              if (consistent[i][k][a * nk + c] != 0 && consistent[j][k][b * nk + c] != 0) {
                triplets.push_back({{static_cast<int>(i), static_cast<int>(j), static_cast<int>(k)},
                                    {features[i].cad[a], features[j].cad[b], features[k].cad[c]}});
              }
            }
          }
        }
      }
    }
  }
  return triplets;
}

// The rigid fit of every triplet whose normals agree after it, scored by eq. 14, in the
// triplets' order. The fits are independent, so they run in parallel; the list is the same for
// any thread count.
std::vector<Fit> fitTriplets(const SurfaceGraph& scan,
                             const SurfaceGraph& cad,
                             const CorrespondenceResult& candidates,
                             const std::vector<Triplet>& triplets,
                             double tolerance,
                             double normal_tolerance_deg,
                             bool oriented_normals) {
  const double min_cos = std::cos(normal_tolerance_deg * kDegree);
  const auto& features = candidates.features;
  // Blocks of triplets, each filling its own list, joined in block order.
  constexpr std::size_t kBlock = 1024;
  const std::size_t blocks = (triplets.size() + kBlock - 1) / kBlock;
  std::vector<std::vector<Fit>> block_fits(blocks);
  const auto signed_blocks = static_cast<std::ptrdiff_t>(blocks);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t block = 0; block < signed_blocks; ++block) {
    const std::size_t first = static_cast<std::size_t>(block) * kBlock;
    const std::size_t last = std::min(triplets.size(), first + kBlock);
    for (std::size_t t = first; t < last; ++t) {
      const Triplet& triplet = triplets[t];
      Oriented s[3];
      Eigen::Matrix3d scan_points;
      Eigen::Matrix3d cad_points;
      for (int m = 0; m < 3; ++m) {
        s[m] = cellOf(scan, features[static_cast<std::size_t>(triplet.feature[m])].feature);
        scan_points.col(m) = s[m].point;
        cad_points.col(m) = cad.centroids[static_cast<std::size_t>(triplet.cad[m])];
      }
      Fit fit;
      fit.pose.T_cad_scan = rigidFit(scan_points, cad_points);
      bool normals_agree = true;
      for (int m = 0; m < 3 && normals_agree; ++m) {
        const Eigen::Vector3d n = fit.pose.T_cad_scan.linear() * s[m].normal;
        const Eigen::Vector3d& nc = cad.normals[static_cast<std::size_t>(triplet.cad[m])];
        const double agreement = oriented_normals ? n.dot(nc) : std::abs(n.dot(nc));
        normals_agree = !hasNormal(n) || !hasNormal(nc) || agreement >= min_cos;
      }
      if (!normals_agree) {
        continue;
      }
      for (int m = 0; m < 3; ++m) {
        fit.pose.feature_triplet[m] = triplet.feature[m];
        fit.pose.cad_triplet[m] = triplet.cad[m];
      }
      fit.rarity_rank =
          static_cast<double>(triplet.feature[0] + triplet.feature[1] + triplet.feature[2]);
      scoreByFeatures(scan, cad, candidates, tolerance, &fit.pose);
      block_fits[static_cast<std::size_t>(block)].push_back(fit);
    }
  }
  std::vector<Fit> fits;
  for (const auto& list : block_fits) {
    fits.insert(fits.end(), list.begin(), list.end());
  }
  return fits;
}

}  // namespace

std::vector<std::string> validate(const GlobalRegistrationConfig& config) {
  std::vector<std::string> errors;
  if (!(config.pair_tolerance_cells > 0.0 && std::isfinite(config.pair_tolerance_cells))) {
    errors.push_back("registration.pair_tolerance_cells must be a finite value > 0");
  }
  if (!(config.normal_tolerance_deg > 0.0 && config.normal_tolerance_deg <= 180.0)) {
    errors.push_back("registration.normal_tolerance_deg must be in (0, 180]");
  }
  if (!(config.min_side_ratio >= 0.0 && std::isfinite(config.min_side_ratio))) {
    errors.push_back("registration.min_side_ratio must be a finite value >= 0");
  }
  if (config.max_fits < 1) {
    errors.push_back("registration.max_fits must be at least 1");
  }
  if (config.verified_hypotheses < 1) {
    errors.push_back("registration.verified_hypotheses must be at least 1");
  }
  if (config.verification_points < 3) {
    errors.push_back("registration.verification_points must be at least 3");
  }
  if (config.refined_hypotheses < 1) {
    errors.push_back("registration.refined_hypotheses must be at least 1");
  }
  if (!(config.ambiguity_ratio > 0.0 && config.ambiguity_ratio <= 1.0)) {
    errors.push_back("registration.ambiguity_ratio must be in (0, 1]");
  }
  if (!(config.min_score >= 0.0 && config.min_score < 1.0)) {
    errors.push_back("registration.min_score must be in [0, 1)");
  }
  if (!(config.min_fitness >= 0.0 && config.min_fitness < 1.0)) {
    errors.push_back("registration.min_fitness must be in [0, 1)");
  }
  if (!(config.max_residual_ratio >= 1.0 && std::isfinite(config.max_residual_ratio))) {
    errors.push_back("registration.max_residual_ratio must be a finite ratio >= 1");
  }
  if (!(config.residual_fitness >= 0.0 && config.residual_fitness <= 1.0)) {
    errors.push_back("registration.residual_fitness must be in [0, 1]");
  }
  if (!(config.min_surface_on_cad >= 0.0 && config.min_surface_on_cad <= 1.0)) {
    errors.push_back("registration.min_surface_on_cad must be in [0, 1]");
  }
  if (!(config.verification_distance_cells > 0.0 &&
        std::isfinite(config.verification_distance_cells))) {
    errors.push_back("registration.verification_distance_cells must be a finite value > 0");
  }
  return errors;
}

int countExplainedFeatures(const Eigen::Isometry3d& T_cad_scan,
                           const SurfaceGraph& scan,
                           const SurfaceGraph& cad,
                           const CorrespondenceResult& candidates,
                           double tolerance) {
  PoseHypothesis pose;
  pose.T_cad_scan = T_cad_scan;
  scoreByFeatures(scan, cad, candidates, tolerance, &pose);
  return pose.features_explained;
}

Eigen::Vector3d VerificationSet::centroid() const {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) {
    mean += p / static_cast<double>(points.size());
  }
  return mean;
}

namespace {

// The cells a verification set takes: up to `count` of `n`, evenly spread, deterministic.
std::vector<std::size_t> verificationCells(std::size_t n, std::size_t count) {
  const std::size_t taken = std::min(n, count);
  std::vector<std::size_t> cells(taken);
  for (std::size_t i = 0; i < taken; ++i) {
    cells[i] = i * n / taken;
  }
  return cells;
}

}  // namespace

VerificationSet makeVerificationSet(const SurfaceGraph& scan, std::size_t count, bool oriented) {
  VerificationSet set;
  set.oriented = oriented;
  for (const std::size_t cell : verificationCells(scan.size(), count)) {
    set.points.push_back(scan.centroids[cell]);
    set.normals.push_back(scan.normals[cell]);
  }
  return set;
}

VerificationSet makeVerificationSet(const SurfaceGraph& scan,
                                    std::size_t count,
                                    bool oriented,
                                    const Points& positions) {
  VerificationSet set = makeVerificationSet(scan, count, oriented);
  std::vector<Eigen::Vector3d> sums(scan.size(), Eigen::Vector3d::Zero());
  std::vector<int> counts(scan.size(), 0);
  const std::size_t known = std::min(positions.size(), scan.point_cell.size());
  for (std::size_t i = 0; i < known; ++i) {
    const int cell = scan.point_cell[i];
    if (cell >= 0 && static_cast<std::size_t>(cell) < scan.size() && positions[i].allFinite()) {
      sums[static_cast<std::size_t>(cell)] += positions[i];
      ++counts[static_cast<std::size_t>(cell)];
    }
  }
  const std::vector<std::size_t> cells = verificationCells(scan.size(), count);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (counts[cells[i]] > 0) {
      set.points[i] = sums[cells[i]] / static_cast<double>(counts[cells[i]]);
    }
  }
  return set;
}

std::vector<double> verificationTerms(const Eigen::Isometry3d& T_cad_scan,
                                      const VerificationSet& set,
                                      const MeshQuery& cad,
                                      double truncation,
                                      double normal_tolerance_deg) {
  // A point counts where some surface facing its way lies within τ, so where the noise pushed a
  // point on a thin wall does not decide which of two poses explains it. Serial, like the score.
  const double min_cos = std::cos(normal_tolerance_deg * kDegree);
  std::vector<double> terms(set.points.size(), 0.0);
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    const Eigen::Vector3d normal = T_cad_scan.linear() * set.normals[i];
    const Eigen::Vector3d point = T_cad_scan * set.points[i];
    const ClosestPoint closest =
        hasNormal(normal) ? cad.closestFacing(point, normal, min_cos, set.oriented, truncation)
                          : cad.closest(point, truncation);
    if (closest.found) {
      terms[i] = 1.0 - std::pow(closest.distance / truncation, 2);
    }
  }
  return terms;
}

double verificationScore(const Eigen::Isometry3d& T_cad_scan,
                         const VerificationSet& set,
                         const MeshQuery& cad,
                         double truncation,
                         double normal_tolerance_deg,
                         double floor) {
  // Serial: callers score many poses in parallel instead (one parallel region per batch of
  // poses, not per pose, so a busy core does not stall every call). The nearest surface only:
  // the ranking of hypotheses was settled with it, and it is the cheaper query.
  if (set.points.empty()) {
    return 0.0;
  }
  const double min_cos = std::cos(normal_tolerance_deg * kDegree);
  const auto count = static_cast<double>(set.points.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    // Each term is at most 1: once even a perfect rest cannot reach the floor, that bound is
    // the answer.
    const double best_possible = (sum + (count - static_cast<double>(i))) / count;
    if (best_possible < floor) {
      return best_possible;
    }
    const ClosestPoint closest = cad.closest(T_cad_scan * set.points[i], truncation);
    if (!closest.found) {
      continue;
    }
    const Eigen::Vector3d normal = T_cad_scan.linear() * set.normals[i];
    const double agreement =
        set.oriented ? normal.dot(closest.normal) : std::abs(normal.dot(closest.normal));
    if (hasNormal(normal) && agreement < min_cos) {
      continue;
    }
    sum += 1.0 - std::pow(closest.distance / truncation, 2);
  }
  return sum / static_cast<double>(set.points.size());
}

namespace {

// The points only `a` explains and those only `b` explains (terms > 0 in one, not the other).
std::pair<double, double> exclusivelyExplained(const std::vector<double>& a,
                                               const std::vector<double>& b) {
  const std::size_t count = std::min(a.size(), b.size());
  double only_a = 0.0;
  double only_b = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    only_a += a[i] > 0.0 && !(b[i] > 0.0) ? 1.0 : 0.0;
    only_b += b[i] > 0.0 && !(a[i] > 0.0) ? 1.0 : 0.0;
  }
  return {only_a, only_b};
}

bool leans(double only_a, double only_b, double sigmas) {
  return only_a > only_b && only_a - only_b >= sigmas * std::sqrt(only_a + only_b);
}

}  // namespace

bool scanPrefers(const std::vector<double>& a, const std::vector<double>& b) {
  constexpr double kMinRatio = 2.0;
  constexpr double kSigmas = 3.0;
  constexpr double kMinShare = 0.01;  // of the points: a feature, not a few stray ones
  const auto [only_a, only_b] = exclusivelyExplained(a, b);
  const auto count = static_cast<double>(std::min(a.size(), b.size()));
  return only_a > 0.0 && only_a >= kMinShare * count && only_a >= kMinRatio * only_b &&
         leans(only_a, only_b, kSigmas);
}

bool scanLeans(const std::vector<double>& a,
               const std::vector<double>& b,
               double sigmas,
               double min_share) {
  const auto [only_a, only_b] = exclusivelyExplained(a, b);
  const auto count = static_cast<double>(std::min(a.size(), b.size()));
  return only_a >= min_share * count && leans(only_a, only_b, sigmas);
}

namespace {

// The separation of poses a result lists apart (separatePoses, poseGap).
constexpr double kSeparateDeg = 10.0;
constexpr double kSeparateCells = 3.0;

}  // namespace

PoseDifference poseDifference(const Eigen::Isometry3d& a,
                              const Eigen::Isometry3d& b,
                              const Eigen::Vector3d& reference) {
  const Eigen::AngleAxisd relative(a.linear().transpose() * b.linear());
  return {std::abs(relative.angle()), (a * reference - b * reference).norm()};
}

bool distinctPoses(const Eigen::Isometry3d& a,
                   const Eigen::Isometry3d& b,
                   const Eigen::Vector3d& reference,
                   double angle_deg,
                   double distance) {
  const auto [angle, shift] = poseDifference(a, b, reference);
  return angle > angle_deg * kDegree || shift > distance;
}

bool separatePoses(const Eigen::Isometry3d& a,
                   const Eigen::Isometry3d& b,
                   const Eigen::Vector3d& reference,
                   double cell_size) {
  return distinctPoses(a, b, reference, kSeparateDeg, kSeparateCells * cell_size);
}

double poseGap(const Eigen::Isometry3d& a,
               const Eigen::Isometry3d& b,
               const Eigen::Vector3d& reference,
               double cell_size) {
  const auto [angle, shift] = poseDifference(a, b, reference);
  return std::max(angle / (kSeparateDeg * kDegree), shift / (kSeparateCells * cell_size));
}

bool refinedOnto(const Eigen::Isometry3d& best,
                 const Eigen::Isometry3d& found,
                 const Eigen::Isometry3d& refined,
                 const Eigen::Vector3d& reference,
                 double cell_size,
                 double share) {
  const double left = poseGap(best, refined, reference, cell_size);
  return left <= 1.0 && left <= (1.0 - share) * poseGap(best, found, reference, cell_size);
}

namespace {

// Verification scores of the hypotheses, in batches of a fixed size. From the second batch on, a
// hypothesis whose score cannot reach the `ranked`-th best of those scored before it is dropped
// (verificationScore's floor): it ranks below the `ranked` best whatever follows, so these keep
// their exact scores, and the batches fix which hypotheses are dropped whatever the thread count.
void scoreRanked(std::vector<PoseHypothesis>* hypotheses,
                 const VerificationSet& set,
                 const MeshQuery& cad,
                 double truncation,
                 double normal_tolerance_deg,
                 std::size_t ranked) {
  constexpr long kBatch = 16;
  const auto count = static_cast<long>(hypotheses->size());
  std::vector<double> scored;  // scores of the hypotheses kept so far
  std::vector<char> dropped(hypotheses->size(), 0);
  for (long start = 0; start < count; start += kBatch) {
    double floor = -std::numeric_limits<double>::infinity();
    if (ranked > 0 && scored.size() >= ranked) {
      std::nth_element(scored.begin(),
                       scored.begin() + static_cast<long>(ranked - 1),
                       scored.end(),
                       std::greater<>());
      floor = scored[ranked - 1];
    }
    const long end = std::min(count, start + kBatch);
#pragma omp parallel for schedule(dynamic, 1)
    for (long h = start; h < end; ++h) {
      auto& hypothesis = (*hypotheses)[static_cast<std::size_t>(h)];
      hypothesis.score = verificationScore(
          hypothesis.T_cad_scan, set, cad, truncation, normal_tolerance_deg, floor);
    }
    for (long h = start; h < end; ++h) {
      const double score = (*hypotheses)[static_cast<std::size_t>(h)].score;
      if (score < floor) {
        dropped[static_cast<std::size_t>(h)] = 1;
      } else {
        scored.push_back(score);
      }
    }
  }
  std::size_t kept = 0;
  for (std::size_t h = 0; h < hypotheses->size(); ++h) {
    if (dropped[h] == 0) {
      (*hypotheses)[kept++] = (*hypotheses)[h];
    }
  }
  hypotheses->resize(kept);
}

}  // namespace

GlobalRegistrationResult registerGlobally(const SurfaceGraph& scan,
                                          const SurfaceGraph& cad,
                                          const CorrespondenceResult& candidates,
                                          const MeshQuery& cad_mesh,
                                          double cell_size,
                                          double r_max,
                                          const GlobalRegistrationConfig& config,
                                          bool oriented_normals) {
  GlobalRegistrationResult result;
  const auto& features = candidates.features;
  const std::size_t f_count = features.size();
  const double tolerance = config.pair_tolerance_cells * cell_size;
  const PairCheck check{tolerance, config.normal_tolerance_deg * kDegree};
  const double min_side = config.min_side_ratio * r_max;

  // Pairwise table (the triangle check, one side at a time).
  PairTable consistent(f_count, std::vector<std::vector<char>>(f_count));
  for (std::size_t i = 0; i < f_count; ++i) {
    const Oriented fi = cellOf(scan, features[i].feature);
    for (std::size_t j = i + 1; j < f_count; ++j) {
      const Oriented fj = cellOf(scan, features[j].feature);
      if ((fj.point - fi.point).norm() < min_side) {
        continue;  // too short a side for a stable fit
      }
      auto& table = consistent[i][j];
      table.assign(features[i].cad.size() * features[j].cad.size(), 0);
      for (std::size_t a = 0; a < features[i].cad.size(); ++a) {
        const Oriented ca = cellOf(cad, features[i].cad[a]);
        for (std::size_t b = 0; b < features[j].cad.size(); ++b) {
          table[a * features[j].cad.size() + b] =
              check(fi, fj, ca, cellOf(cad, features[j].cad[b])) ? 1 : 0;
        }
      }
    }
  }

  const std::vector<Triplet> triplets =
      enumerateTriplets(scan, features, consistent, min_side, config.max_fits);
  result.consistent_triplets = triplets.size();
  std::vector<Fit> fits = fitTriplets(
      scan, cad, candidates, triplets, tolerance, config.normal_tolerance_deg, oriented_normals);
  if (fits.empty()) {
    result.status =
        Status::failure(StatusCode::kRegistrationFailed,
                        "no consistent feature triplet: none of the " + std::to_string(f_count) +
                            " scan features form a triangle congruent with their CAD candidates");
    return result;
  }
  std::sort(fits.begin(), fits.end(), betterFit);

  // The best distinct fits are verified against the whole scan.
  const VerificationSet set =
      makeVerificationSet(scan, config.verification_points, oriented_normals);
  const Eigen::Vector3d reference = set.centroid();
  const double truncation = config.verification_distance_cells * cell_size;
  for (const Fit& fit : fits) {
    const bool distinct = std::all_of(
        result.hypotheses.begin(), result.hypotheses.end(), [&](const PoseHypothesis& kept) {
          return distinctPoses(kept.T_cad_scan, fit.pose.T_cad_scan, reference, 5.0, tolerance);
        });
    if (!distinct) {
      continue;
    }
    result.hypotheses.push_back(fit.pose);
    if (static_cast<int>(result.hypotheses.size()) >= config.verified_hypotheses) {
      break;
    }
  }
  scoreRanked(&result.hypotheses,
              set,
              cad_mesh,
              truncation,
              config.normal_tolerance_deg,
              static_cast<std::size_t>(config.refined_hypotheses));
  std::stable_sort(
      result.hypotheses.begin(),
      result.hypotheses.end(),
      [](const PoseHypothesis& a, const PoseHypothesis& b) { return a.score > b.score; });
  result.correspondences = static_cast<std::size_t>(result.hypotheses.front().features_explained);
  return result;
}

}  // namespace freeform_inspection
