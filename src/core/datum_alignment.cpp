// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/datum_alignment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "pipeline_internal.h"
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "freeform_inspection/global_registration.h"
#include "freeform_inspection/mesh_query.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The rounds stop once no target moves by more than this share of its radius: far below any
// reading's noise (the median of a few dozen points).
constexpr double kSettledShareOfRadius = 1e-3;

struct Target {
  const ComparisonPointConfig* config = nullptr;
  PlacedPoint place;
};

std::string quoted(const Target& target) {
  return "datum target '" + target.config->name + "' (" + target.config->datum + ")";
}

std::string direction(const Eigen::Vector3d& v) {
  const Eigen::Vector3d u = v.normalized();
  char text[64];
  std::snprintf(text, sizeof(text), "(%.2f, %.2f, %.2f)", u.x(), u.y(), u.z());
  return text;
}

// The targets' constraints, one row each: the change of the deviation at target i under a small
// turn ω (scaled by `spread`) about `centre` and a shift v is (p_i − c) × n_i · ω + n_i · v.
Eigen::MatrixXd constraints(const std::vector<Target>& targets,
                            const Eigen::Vector3d& centre,
                            double spread) {
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(targets.size()), 6);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const PlacedPoint& p = targets[i].place;
    const auto r = static_cast<Eigen::Index>(i);
    rows.block<1, 3>(r, 0) = ((p.nominal - centre).cross(p.normal) / spread).transpose();
    rows.block<1, 3>(r, 3) = p.normal.transpose();
  }
  return rows;
}

// The rows of each datum's targets, in the datums' order; none when alike (precedenceSolve()
// fits every row at once after the groups).
std::vector<std::vector<Eigen::Index>> datumGroups(const std::vector<Target>& targets,
                                                   const std::vector<std::string>& order) {
  std::vector<std::vector<Eigen::Index>> groups;
  for (const std::string& datum : order) {
    groups.emplace_back();
    for (std::size_t i = 0; i < targets.size(); ++i) {
      if (targets[i].config->datum == datum) {
        groups.back().push_back(static_cast<Eigen::Index>(i));
      }
    }
  }
  return groups;
}

// The linear map S from the readings to cancel to the motion that cancels them, datum by datum
// (least squares in order of precedence): each datum's rows are fitted by the motions the datums
// before it left free, as far as they hold them (singular values from kMinDatumConditioning of
// the scheme's strongest); what is still free then is fitted to every target at once. Without
// groups that is plain least squares, S = the pseudo-inverse. Fixed by the nominal targets, so
// computed once for every round.
Eigen::MatrixXd precedenceSolve(const Eigen::MatrixXd& rows,
                                const std::vector<std::vector<Eigen::Index>>& groups,
                                double strongest) {
  const Eigen::Index n = rows.rows();
  Eigen::MatrixXd solve = Eigen::MatrixXd::Zero(6, n);
  Eigen::MatrixXd free = Eigen::MatrixXd::Identity(6, 6);  // orthonormal columns
  const auto fit = [&](const std::vector<Eigen::Index>& group) {
    if (group.empty() || free.cols() == 0) {
      return;
    }
    const auto size = static_cast<Eigen::Index>(group.size());
    Eigen::MatrixXd group_rows(size, 6);
    Eigen::MatrixXd picked = Eigen::MatrixXd::Zero(size, n);  // the group's readings
    for (Eigen::Index r = 0; r < size; ++r) {
      group_rows.row(r) = rows.row(group[static_cast<std::size_t>(r)]);
      picked(r, group[static_cast<std::size_t>(r)]) = 1.0;
    }
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(group_rows * free,
                                                Eigen::ComputeThinU | Eigen::ComputeFullV);
    const Eigen::VectorXd& values = svd.singularValues();
    Eigen::Index held = 0;
    while (held < values.size() && values(held) >= kMinDatumConditioning * strongest) {
      ++held;
    }
    if (held == 0) {
      return;
    }
    // What the group's readings ask after the datums before it, fitted within the free motions.
    const Eigen::MatrixXd left = picked - group_rows * solve;
    solve += free * svd.matrixV().leftCols(held) * values.head(held).cwiseInverse().asDiagonal() *
             svd.matrixU().leftCols(held).transpose() * left;
    free = (free * svd.matrixV().rightCols(free.cols() - held)).eval();
  };
  for (const std::vector<Eigen::Index>& group : groups) {
    fit(group);
  }
  std::vector<Eigen::Index> all(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    all[static_cast<std::size_t>(i)] = i;
  }
  fit(all);
  return solve;
}

// Reads every target at a pose. Only the points that can be read are queried on the CAD: with
// q − nominal = a·n + t (t across the normal n), a point's foot q − d·n lies at (a − d)·n + t from
// the nominal, so within the radius r only if |t| ≤ r, and, with |d| ≤ max_distance, only if
// |a| ≤ max_distance + r: a cylinder along the normal. The points of that cylinder widened by r
// are gathered from the whole scan once, and again only when the pose has since moved some point
// of the wide cylinder by more than r (one pass over a 1M-point scan, not one per round).
class TargetReader {
 public:
  TargetReader(const MeshQuery& cad,
               const Points& scan_points,
               const std::vector<Target>& targets,
               double max_distance)
      : cad_(cad), scan_(scan_points), targets_(targets), max_distance_(max_distance) {}

  std::vector<PlaceReading> read(const Eigen::Isometry3d& pose) {
    if (near_.empty() || moved(pose)) {
      gather(pose);
    }
    std::vector<PlaceReading> readings;
    for (std::size_t t = 0; t < targets_.size(); ++t) {
      const PlacedPoint& place = targets_[t].place;
      Points near;
      for (const std::size_t i : near_[t]) {
        const Eigen::Vector3d q = pose * scan_[i];
        if (inCylinder(q, place, 0.0)) {
          near.push_back(q);
        }
      }
      std::vector<float> deviation(near.size(), std::numeric_limits<float>::quiet_NaN());
      const std::vector<ClosestPoint> closest = cad_.closest(near, max_distance_);
      for (std::size_t i = 0; i < near.size(); ++i) {
        if (closest[i].found) {
          deviation[i] = static_cast<float>(closest[i].signed_distance);
        }
      }
      readings.push_back(readAround(place, near, deviation));
    }
    return readings;
  }

 private:
  // In the cylinder a reading comes from, widened by `slack`.
  bool inCylinder(const Eigen::Vector3d& q, const PlacedPoint& place, double slack) const {
    const Eigen::Vector3d v = q - place.nominal;
    const double a = v.dot(place.normal);
    const double across = place.radius + slack;
    return std::abs(a) <= max_distance_ + place.radius + slack &&
           v.squaredNorm() - a * a <= across * across;
  }

  void gather(const Eigen::Isometry3d& pose) {
    gathered_at_ = pose;
    near_.assign(targets_.size(), {});
    for (std::size_t i = 0; i < scan_.size(); ++i) {
      const Eigen::Vector3d q = pose * scan_[i];
      for (std::size_t t = 0; t < targets_.size(); ++t) {
        if (inCylinder(q, targets_[t].place, targets_[t].place.radius)) {
          near_[t].push_back(i);
        }
      }
    }
  }

  // Whether the motion from the gathering's pose to `pose` may move a point of some target's
  // wide cylinder by more than its radius: by at most the move of the nominal plus the turn
  // times the cylinder's reach from it.
  bool moved(const Eigen::Isometry3d& pose) const {
    const Eigen::Isometry3d motion = pose * gathered_at_.inverse();
    const double turn = Eigen::AngleAxisd(motion.linear()).angle();
    for (const Target& target : targets_) {
      const PlacedPoint& place = target.place;
      const double reach = std::hypot(max_distance_ + 2.0 * place.radius, 2.0 * place.radius);
      if ((motion * place.nominal - place.nominal).norm() + turn * reach > place.radius) {
        return true;
      }
    }
    return false;
  }

  const MeshQuery& cad_;
  const Points& scan_;
  const std::vector<Target>& targets_;
  double max_distance_;
  Eigen::Isometry3d gathered_at_ = Eigen::Isometry3d::Identity();
  std::vector<std::vector<std::size_t>> near_;  // per target: indices into the scan
};

// The first target a reading missed, as the reason the alignment stops; empty when all read.
std::string unread(const std::vector<Target>& targets, const std::vector<PlaceReading>& readings) {
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (!readings[i].measured()) {
      return quoted(targets[i]) + " is not measured: " + std::to_string(readings[i].points) +
             " scan point(s) within " + internal::formatLength(targets[i].place.radius) +
             " of it, " + std::to_string(kMinComparisonPoints) + " needed";
    }
  }
  return {};
}

// How far the readings' noise leaves the frame free: each reading is a median of n points of
// standard deviation s, variance (π/2)·s²/n for Gaussian noise, carried through the
// solve (its linear map S): Σ = S·diag(variances)·Sᵀ over the scaled turn
// and the shift at the targets' centre. Reported for the least held axis of each.
void frameSpread(const Eigen::MatrixXd& solve,
                 const std::vector<PlaceReading>& readings,
                 double spread,
                 DatumAlignment* result) {
  const auto n = static_cast<Eigen::Index>(readings.size());
  Eigen::VectorXd variance(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const PlaceReading& r = readings[static_cast<std::size_t>(i)];
    variance(i) = 0.5 * kPi * r.spread * r.spread / static_cast<double>(r.points);
  }
  const Eigen::Matrix<double, 6, 6> covariance = solve * variance.asDiagonal() * solve.transpose();
  const auto largest = [](const Eigen::Matrix3d& block) {
    return std::sqrt(std::max(
        0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(block).eigenvalues().maxCoeff()));
  };
  result->rotation_std_deg =
      largest(covariance.topLeftCorner<3, 3>() / (spread * spread)) * 180.0 / kPi;
  result->translation_std = largest(covariance.bottomRightCorner<3, 3>());
}

}  // namespace

bool hasDatumTargets(const std::vector<ComparisonPointConfig>& points) {
  return std::any_of(points.begin(), points.end(), [](const ComparisonPointConfig& p) {
    return !p.datum.empty();
  });
}

std::vector<std::string> datumOrder(const DatumPrecedence& precedence,
                                    const std::vector<ComparisonPointConfig>& points) {
  if (precedence.alike) {
    return {};
  }
  if (!precedence.order.empty()) {
    return precedence.order;
  }
  std::set<std::string> labels;
  for (const ComparisonPointConfig& point : points) {
    if (!point.datum.empty()) {
      labels.insert(point.datum);
    }
  }
  return {labels.begin(), labels.end()};
}

std::string datumPrecedenceText(const DatumPrecedence& precedence,
                                const std::vector<ComparisonPointConfig>& points) {
  if (precedence.alike) {
    return "none (every target alike)";
  }
  std::string text;
  for (const std::string& datum : datumOrder(precedence, points)) {
    text += (text.empty() ? "" : ", ") + datum;
  }
  return text;
}

DatumAlignment alignToDatums(const MeshQuery& cad,
                             const Points& scan_points,
                             const Eigen::Isometry3d& T_cad_scan,
                             const std::vector<ComparisonPointConfig>& points,
                             const DatumPrecedence& precedence,
                             double default_radius,
                             double max_distance) {
  DatumAlignment result;
  result.T_cad_scan_best_fit = T_cad_scan;
  result.requested = hasDatumTargets(points);
  if (!result.requested) {
    return result;
  }
  std::vector<Target> targets;
  for (const ComparisonPointConfig& point : points) {
    if (!point.datum.empty()) {
      targets.push_back({&point, placeComparisonPoint(point, cad, default_radius)});
    }
  }
  for (const Target& target : targets) {
    DatumTargetReading reading;
    reading.name = target.config->name;
    reading.datum = target.config->datum;
    reading.nominal = target.place.nominal;
    reading.normal = target.place.normal;
    result.targets.push_back(reading);
  }
  for (const Target& target : targets) {
    if (!target.place.near_surface()) {
      result.message = quoted(target) + " lies " +
                       (target.place.found ? internal::formatLength(target.place.off_surface)
                                           : std::string("nowhere")) +
                       " off the CAD surface";
      return result;
    }
  }
  if (targets.size() < kMinDatumTargets) {
    result.message = std::to_string(targets.size()) + " datum target(s) fix at most " +
                     std::to_string(targets.size()) + " of the pose's 6 degrees of freedom; " +
                     std::to_string(kMinDatumTargets) + " are needed (3-2-1)";
    return result;
  }
  // Turns about the targets' centre, scaled by their spread, so the constraints' singular values
  // compare a turn with a shift.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Target& target : targets) {
    centre += target.place.nominal;
  }
  centre /= static_cast<double>(targets.size());
  double spread = 0.0;
  for (const Target& target : targets) {
    spread += (target.place.nominal - centre).squaredNorm();
  }
  spread = std::sqrt(spread / static_cast<double>(targets.size()));
  if (!(spread > 0.0)) {
    result.message = "the datum targets all lie at one place: they fix no turn of the pose";
    return result;
  }
  const Eigen::MatrixXd rows = constraints(targets, centre, spread);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(rows, Eigen::ComputeFullV);
  const Eigen::VectorXd& values = svd.singularValues();
  result.conditioning = values(5) / values(0);
  if (!(result.conditioning >= kMinDatumConditioning)) {
    const Eigen::VectorXd free = svd.matrixV().col(5);
    const bool shift = free.tail<3>().norm() >= free.head<3>().norm();
    char held[96];
    std::snprintf(held,
                  sizeof(held),
                  " (their normals hold it %.3g of the strongest motion, %.3g needed)",
                  result.conditioning,
                  kMinDatumConditioning);
    result.message = "the datum targets leave the pose free to " +
                     (shift ? "shift along " + direction(free.tail<3>())
                            : "turn about an axis along " + direction(free.head<3>())) +
                     held + ": the targets need normals along it";
    return result;
  }
  result.precedence = datumOrder(precedence, points);
  const Eigen::MatrixXd solve =
      precedenceSolve(rows, datumGroups(targets, result.precedence), values(0));
  double settled = std::numeric_limits<double>::infinity();
  for (const Target& target : targets) {
    settled = std::min(settled, kSettledShareOfRadius * target.place.radius);
  }

  Eigen::Isometry3d pose = T_cad_scan;
  TargetReader reader(cad, scan_points, targets, max_distance);
  std::vector<PlaceReading> readings = reader.read(pose);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    result.targets[i].best_fit = readings[i].deviation;
  }
  double step = std::numeric_limits<double>::infinity();
  while (true) {
    const std::string missing = unread(targets, readings);
    if (!missing.empty()) {
      result.message = missing;
      for (std::size_t i = 0; i < targets.size(); ++i) {
        result.targets[i].points = readings[i].points;
      }
      return result;
    }
    if (step <= settled || result.rounds == kMaxDatumRounds) {
      break;
    }
    Eigen::VectorXd deviation(static_cast<Eigen::Index>(targets.size()));
    for (std::size_t i = 0; i < targets.size(); ++i) {
      deviation(static_cast<Eigen::Index>(i)) = readings[i].deviation;
    }
    const Eigen::VectorXd motion = solve * -deviation;
    const Eigen::Vector3d turn = motion.head<3>() / spread;
    const Eigen::Vector3d shift = motion.tail<3>();
    step = 0.0;
    for (const Target& target : targets) {
      step = std::max(step, (turn.cross(target.place.nominal - centre) + shift).norm());
    }
    const double angle = turn.norm();
    const Eigen::Matrix3d rotation = angle > 0.0
                                         ? Eigen::AngleAxisd(angle, turn / angle).toRotationMatrix()
                                         : Eigen::Matrix3d::Identity();
    Eigen::Isometry3d correction = Eigen::Isometry3d::Identity();
    correction.linear() = rotation;
    correction.translation() = centre + shift - rotation * centre;
    pose = correction * pose;
    ++result.rounds;
    readings = reader.read(pose);
  }
  for (std::size_t i = 0; i < targets.size(); ++i) {
    result.targets[i].points = readings[i].points;
    result.targets[i].aligned = readings[i].deviation;
  }
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : scan_points) {
    centroid += p;
  }
  centroid /= static_cast<double>(std::max<std::size_t>(scan_points.size(), 1));
  const PoseDifference moved = poseDifference(T_cad_scan, pose, centroid);
  result.aligned = true;
  result.turn_deg = moved.angle * 180.0 / kPi;
  result.shift = moved.shift;
  frameSpread(solve, readings, spread, &result);
  const std::string order = result.precedence.empty()
                                ? "every target alike"
                                : "in the order " + datumPrecedenceText(precedence, points);
  char text[384];
  std::snprintf(text,
                sizeof(text),
                "aligned to %zu datum targets (%s) in %d round(s)%s: %.4g deg and %.4g mm from the "
                "best fit; the readings' noise leaves the frame %.2g deg and %.2g mm (1 sigma)",
                targets.size(),
                order.c_str(),
                result.rounds,
                step <= settled ? "" : " (stopped at the limit, not settled)",
                result.turn_deg,
                result.shift * 1e3,
                result.rotation_std_deg,
                result.translation_std * 1e3);
  result.message = text;
  result.T_cad_scan = pose;
  return result;
}

}  // namespace freeform_inspection
