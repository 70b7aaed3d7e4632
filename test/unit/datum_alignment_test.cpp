// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// Datum alignment on a box 100 x 60 x 40 mm whose top face stands 0.5 mm too high: the datum
// targets on the bottom and two sides (3-2-1) must bring back the pose those faces define, which
// the best fit would tilt and lift to share the top's error; and schemes that cannot fix a pose
// are refused with the reason.
#include "freeform_inspection/datum_alignment.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "test_shapes.h"
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/pipeline.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;
const Eigen::Vector3d kHalf(0.05, 0.03, 0.02);
constexpr double kTopRaised = 0.0005;  // the part is 0.5 mm taller than its CAD
constexpr double kSpacing = 0.0005;    // scan points every 0.5 mm
constexpr double kRadius = 0.003;      // each target read over 3 mm
constexpr double kReach = 0.005;       // the deviation map's cut-off

const MeshQuery& box() {
  static const MeshQuery query(test::makeBox(kHalf));
  return query;
}

// The part where the CAD's box is, faces on a grid, the top raised; `sigma` of noise along each
// face's normal (drawn from `seed`); `without_x_low`: the face x = −hx not scanned.
Points partSurface(double sigma, bool without_x_low = false, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma > 0.0 ? sigma : 1.0);
  Points points;
  const auto face = [&](int axis, double side) {
    const int a = (axis + 1) % 3;
    const int b = (axis + 2) % 3;
    const int na = static_cast<int>(std::floor(kHalf[a] / kSpacing));
    const int nb = static_cast<int>(std::floor(kHalf[b] / kSpacing));
    for (int i = -na + 1; i < na; ++i) {
      for (int j = -nb + 1; j < nb; ++j) {
        Eigen::Vector3d p;
        p[a] = i * kSpacing;
        p[b] = j * kSpacing;
        p[axis] = side * kHalf[axis] + (axis == 2 && side > 0 ? kTopRaised : 0.0);
        p[axis] += sigma > 0.0 ? side * noise(rng) : 0.0;
        points.push_back(p);
      }
    }
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {-1.0, 1.0}) {
      if (!(without_x_low && axis == 0 && side < 0)) {
        face(axis, side);
      }
    }
  }
  return points;
}

ComparisonPointConfig target(const std::string& name, const Eigen::Vector3d& at) {
  ComparisonPointConfig point;
  point.name = name;
  point.datum = name.substr(0, 1);
  point.position = at;
  point.radius = kRadius;
  return point;
}

// 3-2-1: three on the bottom (z = −hz), two on the side y = −hy, one on the end x = −hx.
std::vector<ComparisonPointConfig> nest() {
  return {target("A1", {-0.035, -0.018, -kHalf.z()}),
          target("A2", {0.035, -0.018, -kHalf.z()}),
          target("A3", {0.0, 0.018, -kHalf.z()}),
          target("B1", {-0.03, -kHalf.y(), 0.0}),
          target("B2", {0.03, -kHalf.y(), 0.0}),
          target("C1", {-kHalf.x(), 0.0, 0.0})};
}

// Where the scanner saw the part: the scan frame is the CAD frame moved by `truth`⁻¹.
Eigen::Isometry3d truth() {
  return Eigen::Translation3d(0.2, -0.1, 0.4) *
         Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, -1.0).normalized());
}

Points inScanFrame(const Points& part) {
  Points scan;
  for (const Eigen::Vector3d& p : part) {
    scan.push_back(truth().inverse() * p);
  }
  return scan;
}

// A best fit that shared the top's error: lifted and tilted.
Eigen::Isometry3d bestFit() {
  return Eigen::Translation3d(0.0002, -0.0003, -0.00025) *
         Eigen::AngleAxisd(0.4 * kPi / 180.0, Eigen::Vector3d(0.3, 1.0, 0.2).normalized()) *
         truth();
}

// [m] How far a pose puts any corner of the part from where the truth puts it.
double largestMove(const Eigen::Isometry3d& pose) {
  double largest = 0.0;
  for (const Eigen::Vector3d& corner : test::makeBox(kHalf).vertices) {
    largest = std::max(largest, (pose * (truth().inverse() * corner) - corner).norm());
  }
  return largest;
}

double angleDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / kPi;
}

TEST(DatumAlignment, ThreeTwoOneBringsBackTheFrameTheDatumFacesDefine) {
  const Points scan = inScanFrame(partSurface(0.0));
  const DatumAlignment aligned = alignToDatums(box(), scan, bestFit(), nest(), {}, 0.001, kReach);
  ASSERT_TRUE(aligned.requested);
  ASSERT_TRUE(aligned.aligned) << aligned.message;
  EXPECT_LT(angleDeg(aligned.T_cad_scan, truth()), 1e-6);
  EXPECT_LT(largestMove(aligned.T_cad_scan), 1e-8);
  EXPECT_GT(aligned.conditioning, kMinDatumConditioning);
  EXPECT_LE(aligned.rounds, 5);
  ASSERT_EQ(aligned.targets.size(), 6u);
  double largest_before = 0.0;
  for (const DatumTargetReading& t : aligned.targets) {
    EXPECT_LT(std::abs(t.aligned), 1e-8) << t.name;
    EXPECT_GT(t.points, 100u) << t.name;  // π·(3 mm)² at 0.5 mm spacing: about 113
    largest_before = std::max(largest_before, std::abs(t.best_fit));
  }
  EXPECT_GT(largest_before, 1e-4);  // the best fit missed the targets by 0.1 mm or more
  // How far it moved: the best fit's 0.4° back to the truth.
  EXPECT_NEAR(aligned.turn_deg, 0.4, 1e-3);
  EXPECT_EQ(aligned.T_cad_scan_best_fit.matrix(), bestFit().matrix());
  // Measured in the datum frame, the top reads its whole 0.5 mm.
  const ClosestPoint top =
      box().closest(aligned.T_cad_scan * (truth().inverse() * Eigen::Vector3d(0.01, 0.01, 0.0205)));
  EXPECT_NEAR(top.signed_distance, kTopRaised, 1e-8);
}

// From a start 2° and 5 mm off (beyond the 3 mm the targets are read over) the readings are
// gathered again as the pose moves, and the frame is the same.
TEST(DatumAlignment, AFarStartEndsInTheSameFrame) {
  const Points scan = inScanFrame(partSurface(0.0));
  const Eigen::Isometry3d far =
      Eigen::Translation3d(0.003, -0.004, 0.0) *
      Eigen::AngleAxisd(2.0 * kPi / 180.0, Eigen::Vector3d(1.0, -0.5, 0.3).normalized()) * truth();
  const DatumAlignment aligned = alignToDatums(box(), scan, far, nest(), {}, 0.001, kReach);
  ASSERT_TRUE(aligned.aligned) << aligned.message;
  EXPECT_LT(angleDeg(aligned.T_cad_scan, truth()), 1e-6);
  EXPECT_LT(largestMove(aligned.T_cad_scan), 1e-8);
  EXPECT_NEAR(aligned.turn_deg, 2.0, 1e-6);
  EXPECT_GT(aligned.shift, 0.003);
}

TEST(DatumAlignment, NoisyReadingsMoveThePoseByTheirMediansErrorOnly) {
  const double sigma = 2e-5;  // 0.02 mm along the normals
  const Points scan = inScanFrame(partSurface(sigma));
  const DatumAlignment aligned = alignToDatums(box(), scan, bestFit(), nest(), {}, 0.001, kReach);
  ASSERT_TRUE(aligned.aligned) << aligned.message;
  // Each reading is the median of ~113 points: about 1.25 σ / √113 = 2.4 µm. Over levers of 36
  // to 70 mm that turns the pose by a few thousandths of a degree.
  EXPECT_LT(angleDeg(aligned.T_cad_scan, truth()), 0.02);
  EXPECT_LT(largestMove(aligned.T_cad_scan), 1e-5);
  for (const DatumTargetReading& t : aligned.targets) {
    EXPECT_LT(std::abs(t.aligned), 0.25 * sigma) << t.name;
  }
}

// The spread the alignment reports for its frame is the spread it has: over 24 noise draws the
// frame's errors about their least held axis and along their least held direction match the
// reported 1σ (a sample of 24 gives its standard deviation within about ±30 %). For 3-2-1, and
// for eight targets fixed in order of precedence (a fourth on the bottom, one on the raised top
// that nothing is left for).
void expectTheReportedSpread(const std::vector<ComparisonPointConfig>& targets) {
  const double sigma = 2e-5;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d turns = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d shifts = Eigen::Matrix3d::Zero();
  double rotation_std = 0.0;
  double translation_std = 0.0;
  constexpr int kDraws = 24;
  for (int draw = 0; draw < kDraws; ++draw) {
    const Points scan = inScanFrame(partSurface(sigma, false, 100 + draw));
    const DatumAlignment aligned =
        alignToDatums(box(), scan, bestFit(), targets, {}, 0.001, kReach);
    ASSERT_TRUE(aligned.aligned) << aligned.message;
    if (draw == 0) {
      for (const DatumTargetReading& t : aligned.targets) {
        centre += t.nominal / static_cast<double>(aligned.targets.size());
      }
    }
    // The frame's error as a motion of the CAD frame: a turn, and the shift of the targets'
    // centre.
    const Eigen::Isometry3d error = aligned.T_cad_scan * truth().inverse();
    const Eigen::AngleAxisd turn(error.linear());
    const Eigen::Vector3d turn_vector = turn.angle() * turn.axis();
    const Eigen::Vector3d shift = error * centre - centre;
    turns += turn_vector * turn_vector.transpose() / kDraws;
    shifts += shift * shift.transpose() / kDraws;
    rotation_std += aligned.rotation_std_deg / kDraws;
    translation_std += aligned.translation_std / kDraws;
  }
  const auto largest = [](const Eigen::Matrix3d& m) {
    return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues().maxCoeff());
  };
  const double observed_turn = largest(turns) * 180.0 / kPi;
  const double observed_shift = largest(shifts);
  std::printf(
      "  1 sigma turn: reported %.3g deg, observed %.3g deg; shift: reported %.3g um, "
      "observed %.3g um\n",
      rotation_std,
      observed_turn,
      translation_std * 1e6,
      observed_shift * 1e6);
  EXPECT_GT(observed_turn, 0.6 * rotation_std);
  EXPECT_LT(observed_turn, 1.6 * rotation_std);
  EXPECT_GT(observed_shift, 0.6 * translation_std);
  EXPECT_LT(observed_shift, 1.6 * translation_std);
}

TEST(DatumAlignment, TheFrameSpreadItReportsIsTheSpreadItHas) {
  expectTheReportedSpread(nest());
  std::vector<ComparisonPointConfig> more = nest();
  more.push_back(target("A4", {0.0, -0.018, -kHalf.z()}));
  more.push_back(target("D1", {0.01, 0.01, kHalf.z()}));
  expectTheReportedSpread(more);
}

// Without precedence (`datum_precedence: none`) every target counts alike.
TEST(DatumAlignment, WithoutPrecedenceMoreTargetsThanSixAreFittedByLeastSquares) {
  std::vector<ComparisonPointConfig> targets = nest();
  targets.push_back(target("A4", {0.0, -0.018, -kHalf.z()}));
  targets.push_back(target("D1", {0.01, 0.01, kHalf.z()}));  // on the raised top
  const Points scan = inScanFrame(partSurface(0.0));
  DatumPrecedence alike;
  alike.alike = true;
  const DatumAlignment aligned =
      alignToDatums(box(), scan, bestFit(), targets, alike, 0.001, kReach);
  ASSERT_TRUE(aligned.aligned) << aligned.message;
  EXPECT_TRUE(aligned.precedence.empty());
  EXPECT_NE(aligned.message.find("(every target alike)"), std::string::npos) << aligned.message;
  // The top's target alone disagrees with the rest: least squares leaves part of its 0.5 mm
  // there and spreads the rest over the bottom's targets.
  EXPECT_GT(std::abs(aligned.targets.back().aligned), 1e-4);
  EXPECT_LT(std::abs(aligned.targets.back().aligned), kTopRaised);
  // At the least-squares pose no small motion lowers the sum of squared readings: the residuals
  // are orthogonal to every target's constraint row (the turn about the origin, the shift).
  Eigen::Matrix<double, 6, 1> gradient = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 1> at_best_fit = Eigen::Matrix<double, 6, 1>::Zero();
  double squares = 0.0;
  for (const DatumTargetReading& t : aligned.targets) {
    Eigen::Matrix<double, 6, 1> row;
    row << t.nominal.cross(t.normal) / 0.05, t.normal;
    gradient += t.aligned * row;
    at_best_fit += t.best_fit * row;
    squares += t.aligned * t.aligned;
  }
  // Zero within the rounds' stop (no target moving by 3 µm or more); at the best fit it is not.
  EXPECT_LT(gradient.norm(), 1e-5) << gradient.transpose();
  EXPECT_GT(at_best_fit.norm(), 1e-4) << at_best_fit.transpose();
  EXPECT_GT(std::sqrt(squares), 2e-4);
}

// Seven targets and one more on the raised top (D1, above the bottom targets' centre): in the
// order A, B, C, D (the default, alphabetical) the bottom, side and end fix the pose where the
// truth has it and D1 reads the top's whole 0.5 mm; with D primary, D1 fixes the height first,
// the part sits 0.5 mm lower and the bottom's targets read it instead.
TEST(DatumAlignment, TheDatumFirstInPrecedenceFixesWhatLaterOnesWouldMove) {
  std::vector<ComparisonPointConfig> targets = nest();
  targets.push_back(target("A4", {0.0, -0.018, -kHalf.z()}));
  targets.push_back(target("D1", {0.0, -0.009, kHalf.z()}));
  const Points scan = inScanFrame(partSurface(0.0));
  const auto reading = [](const DatumAlignment& aligned, const std::string& name) {
    for (const DatumTargetReading& t : aligned.targets) {
      if (t.name == name) {
        return t.aligned;
      }
    }
    return std::numeric_limits<double>::quiet_NaN();
  };

  const DatumAlignment abcd = alignToDatums(box(), scan, bestFit(), targets, {}, 0.001, kReach);
  ASSERT_TRUE(abcd.aligned) << abcd.message;
  EXPECT_EQ(abcd.precedence, (std::vector<std::string>{"A", "B", "C", "D"}));
  EXPECT_NE(abcd.message.find("in the order A, B, C, D"), std::string::npos) << abcd.message;
  EXPECT_LT(angleDeg(abcd.T_cad_scan, truth()), 1e-6);
  EXPECT_LT(largestMove(abcd.T_cad_scan), 1e-8);
  for (const char* name : {"A1", "A2", "A3", "A4", "B1", "B2", "C1"}) {
    EXPECT_LT(std::abs(reading(abcd, name)), 1e-8) << name;
  }
  EXPECT_NEAR(reading(abcd, "D1"), kTopRaised, 1e-8);

  DatumPrecedence d_first;
  d_first.order = {"D", "A", "B", "C"};
  const DatumAlignment dabc =
      alignToDatums(box(), scan, bestFit(), targets, d_first, 0.001, kReach);
  ASSERT_TRUE(dabc.aligned) << dabc.message;
  EXPECT_EQ(dabc.precedence, d_first.order);
  const Eigen::Isometry3d lowered = Eigen::Translation3d(0.0, 0.0, -kTopRaised) * truth();
  EXPECT_LT(angleDeg(dabc.T_cad_scan, lowered), 1e-6);
  EXPECT_LT(largestMove(Eigen::Translation3d(0.0, 0.0, kTopRaised) * dabc.T_cad_scan), 1e-8);
  EXPECT_LT(std::abs(reading(dabc, "D1")), 1e-8);
  for (const char* name : {"A1", "A2", "A3", "A4"}) {
    EXPECT_NEAR(reading(dabc, name), kTopRaised, 1e-8) << name;  // material below the CAD
  }
  for (const char* name : {"B1", "B2", "C1"}) {
    EXPECT_LT(std::abs(reading(dabc, name)), 1e-8) << name;
  }
}

TEST(DatumAlignment, SchemesThatCannotFixThePoseAreRefusedWithTheReason) {
  const Points scan = inScanFrame(partSurface(0.0));
  // Five targets.
  std::vector<ComparisonPointConfig> five = nest();
  five.pop_back();
  DatumAlignment aligned = alignToDatums(box(), scan, bestFit(), five, {}, 0.001, kReach);
  EXPECT_TRUE(aligned.requested);
  EXPECT_FALSE(aligned.aligned);
  EXPECT_NE(aligned.message.find("6 are needed"), std::string::npos) << aligned.message;
  // Six on the bottom: nothing holds a shift along x or y, nor a turn about z.
  const std::vector<ComparisonPointConfig> flat = {target("A1", {-0.035, -0.018, -kHalf.z()}),
                                                   target("A2", {0.035, -0.018, -kHalf.z()}),
                                                   target("A3", {0.0, 0.018, -kHalf.z()}),
                                                   target("A4", {-0.035, 0.018, -kHalf.z()}),
                                                   target("A5", {0.035, 0.018, -kHalf.z()}),
                                                   target("A6", {0.0, 0.0, -kHalf.z()})};
  aligned = alignToDatums(box(), scan, bestFit(), flat, {}, 0.001, kReach);
  EXPECT_FALSE(aligned.aligned);
  EXPECT_NE(aligned.message.find("leave the pose free"), std::string::npos) << aligned.message;
  EXPECT_LT(aligned.conditioning, 1e-9);
  // A target on a face the scan does not show.
  aligned = alignToDatums(box(),
                          inScanFrame(partSurface(0.0, /*without_x_low=*/true)),
                          bestFit(),
                          nest(),
                          {},
                          0.001,
                          kReach);
  EXPECT_FALSE(aligned.aligned);
  EXPECT_NE(aligned.message.find("'C1' (C) is not measured: 0 scan point(s)"), std::string::npos)
      << aligned.message;
  // A target 20 mm off the surface (a position in other units?).
  std::vector<ComparisonPointConfig> off = nest();
  off[3].position.y() -= 0.02;
  aligned = alignToDatums(box(), scan, bestFit(), off, {}, 0.001, kReach);
  EXPECT_FALSE(aligned.aligned);
  EXPECT_NE(aligned.message.find("'B1' (B) lies 20 mm off the CAD surface"), std::string::npos)
      << aligned.message;
  // No datum named: nothing asked, nothing done.
  std::vector<ComparisonPointConfig> plain = nest();
  for (ComparisonPointConfig& p : plain) {
    p.datum.clear();
  }
  aligned = alignToDatums(box(), scan, bestFit(), plain, {}, 0.001, kReach);
  EXPECT_FALSE(aligned.requested);
  EXPECT_FALSE(aligned.aligned);
}

TEST(DatumAlignment, TheDatumKeyIsReadFromThePointsFile) {
  const ComparisonPointsLoadResult read = parseComparisonPoints(
      "points:\n"
      "  - {name: A1, position: [0, 0, 0], datum: A}\n"
      "  - {name: tip, position: [0, 0, 0.1]}\n");
  ASSERT_TRUE(read.status.ok()) << read.status.message;
  ASSERT_EQ(read.points.size(), 2u);
  EXPECT_EQ(read.points[0].datum, "A");
  EXPECT_TRUE(read.points[1].datum.empty());
  const ComparisonPointsLoadResult empty =
      parseComparisonPoints("points:\n  - {name: A1, position: [0, 0, 0], datum: ''}\n");
  EXPECT_FALSE(empty.status.ok());
  EXPECT_NE(empty.status.message.find("datum must name a datum"), std::string::npos)
      << empty.status.message;
}

TEST(DatumAlignment, ThePrecedenceIsReadBesideThePointsAndChecked) {
  const std::string points =
      "points:\n"
      "  - {name: A1, position: [0, 0, 0], datum: A}\n"
      "  - {name: B1, position: [0, 0, 0.1], datum: B}\n"
      "  - {name: C1, position: [0, 0, 0.2], datum: C}\n"
      "  - {name: tip, position: [0, 0, 0.3]}\n";
  ComparisonPointsLoadResult read = parseComparisonPoints(points);
  ASSERT_TRUE(read.status.ok()) << read.status.message;
  EXPECT_FALSE(read.datum_precedence.alike);
  EXPECT_TRUE(read.datum_precedence.order.empty());
  EXPECT_EQ(datumOrder(read.datum_precedence, read.points),
            (std::vector<std::string>{"A", "B", "C"}));

  read = parseComparisonPoints(points + "datum_precedence: [B, C, A]\n");
  ASSERT_TRUE(read.status.ok()) << read.status.message;
  EXPECT_EQ(read.datum_precedence.order, (std::vector<std::string>{"B", "C", "A"}));
  EXPECT_EQ(datumPrecedenceText(read.datum_precedence, read.points), "B, C, A");

  read = parseComparisonPoints(points + "datum_precedence: none\n");
  ASSERT_TRUE(read.status.ok()) << read.status.message;
  EXPECT_TRUE(read.datum_precedence.alike);
  EXPECT_TRUE(datumOrder(read.datum_precedence, read.points).empty());

  const std::vector<std::pair<std::string, std::string>> refused = {
      {"datum_precedence: [A, B]\n", "comparison point 'C1': datum 'C' is not in datum_precedence"},
      {"datum_precedence: [A, B, C, A]\n", "lists datum 'A' twice"},
      {"datum_precedence: [A, B, C, E]\n", "'E', which no comparison point is a target of"},
      {"datum_precedence: []\n", "datum_precedence must list the datums"},
      {"datum_precedence: all\n", "datum_precedence must list the datums"},
      {"datum_precedence: [[A, B], C]\n", "datum_precedence must list the datums"},
      {"precedence: [A, B, C]\n", "unknown key 'precedence'"}};
  for (const auto& [text, expected] : refused) {
    read = parseComparisonPoints(points + text);
    EXPECT_FALSE(read.status.ok()) << text;
    EXPECT_NE(read.status.message.find(expected), std::string::npos)
        << text << ": " << read.status.message;
    EXPECT_TRUE(read.points.empty()) << text;
  }
  // A configuration built in code is checked the same way.
  PipelineConfig config;
  config.comparison_points = parseComparisonPoints(points).points;
  config.datum_precedence.order = {"A", "C"};
  const std::vector<std::string> errors = validate(config);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("datum 'B' is not in datum_precedence"), std::string::npos) << errors[0];
}

}  // namespace
}  // namespace freeform_inspection
