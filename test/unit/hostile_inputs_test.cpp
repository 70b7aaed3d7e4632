// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// Hostile inputs of issue 8 that no other test covers (docs/reliability.md lists them all, with
// the test of each): every one gets its status code and a message naming the problem, and the
// next good call still works.
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "io_test_util.h"
#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/pipeline.h"

#ifndef FREEFORM_DATA_DIR
#error "FREEFORM_DATA_DIR must name the package's data directory"
#endif

namespace freeform_inspection {
namespace {

using io_test::mentions;

const std::string kBlade = std::string(FREEFORM_DATA_DIR) + "/blade/blade.stl";
const std::string kScan = std::string(FREEFORM_DATA_DIR) + "/blade/blade_scan.ply";
const Eigen::Vector3d kHalf(0.05, 0.03, 0.02);  // a 100 × 60 × 40 mm box

const Model& blade() {
  static const std::shared_ptr<const Model> model = [] {
    const ModelLoadResult loaded = loadModel(kBlade, 0.001, "blade");
    EXPECT_TRUE(loaded.status.ok()) << loaded.status.message;
    return loaded.model;
  }();
  return *model;
}

const Scan& sample() {
  static const Scan scan = [] {
    const ScanLoadResult loaded = loadScan(kScan, 1.0);
    EXPECT_TRUE(loaded.status.ok()) << loaded.status.message;
    return loaded.scan;
  }();
  return scan;
}

Scan pointsOnly(const Points& points) {
  Scan scan;
  scan.points = points;
  return scan;
}

// The good call after a bad one: the shipped sample still registers against the shipped blade.
void expectSampleStillRegisters(const PipelineConfig& config = PipelineConfig()) {
  const InspectionResult good = inspect(blade(), sample(), config);
  EXPECT_TRUE(good.status.ok()) << good.status.message;
  EXPECT_EQ(good.registration, RegistrationStatus::kOk) << good.status.message;
}

// A refused scan never comes with a pose or a verdict.
void expectRefused(const InspectionResult& result,
                   StatusCode code,
                   const std::string& words,
                   const std::string& name) {
  EXPECT_EQ(result.status.code, code) << name << ": " << result.status.message;
  EXPECT_TRUE(mentions(result.status.message, words)) << name;
  EXPECT_EQ(result.registration, RegistrationStatus::kFailed) << name;
  EXPECT_EQ(result.verdict, Verdict::kNotEvaluated) << name;
}

std::string tempPath(const std::string& name) {
  return (std::filesystem::path(::testing::TempDir()) / ("hostile_inputs_test_" + name)).string();
}

// ---------------------------------------------------------------- scans ----

TEST(HostileScans, AllInfiniteCloudIsInvalidInput) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Scan scan = pointsOnly({{inf, 0, 0}, {0, -inf, 0}, {0, 0, inf}, {inf, nan, -inf}});
  expectRefused(inspect(blade(), scan, PipelineConfig()),
                StatusCode::kInvalidInput,
                "no finite points (4 received)",
                "all inf");
  expectSampleStillRegisters();
}

TEST(HostileScans, OneTwoAndThreePointsAreDegenerateNamingTheCount) {
  const Model& model = blade();
  expectRefused(inspect(model, pointsOnly({{0.01, 0.02, 0.03}}), PipelineConfig()),
                StatusCode::kDegenerateInput,
                "1 finite points; registration needs at least 3",
                "one point");
  expectRefused(inspect(model, pointsOnly({{0, 0, 0}, {0.05, 0.01, 0}}), PipelineConfig()),
                StatusCode::kDegenerateInput,
                "2 finite points",
                "two points");
  // Three points always lie in a plane: enough for the count, never for the shape.
  expectRefused(
      inspect(model, pointsOnly({{0, 0, 0}, {0.05, 0, 0}, {0, 0.05, 0.01}}), PipelineConfig()),
      StatusCode::kDegenerateInput,
      "planar",
      "three points");
  expectRefused(
      inspect(model, pointsOnly({{0, 0, 0}, {0.05, 0, 0}, {0.1, 0, 0}}), PipelineConfig()),
      StatusCode::kDegenerateInput,
      "collinear",
      "three collinear points");
  // Three finite points among NaN are counted after the NaN are removed.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const InspectionResult with_nan =
      inspect(model,
              pointsOnly({{nan, 0, 0}, {0, 0, 0}, {nan, nan, nan}, {0.05, 0.01, 0}}),
              PipelineConfig());
  expectRefused(with_nan, StatusCode::kDegenerateInput, "2 finite points", "two among NaN");
}

TEST(HostileScans, AllPointsIdenticalIsCollinearNotACrash) {
  const Scan same = pointsOnly(Points(5000, Eigen::Vector3d(0.01, 0.02, 0.03)));
  expectRefused(inspect(blade(), same, PipelineConfig()),
                StatusCode::kDegenerateInput,
                "collinear",
                "identical points");
  expectSampleStillRegisters();
}

// A given pose changes nothing about what a scan must be: inspectFrom() and inspectAt() refuse
// the bad scans above as inspect() does, with the same code and reason, never a pose or verdict.
TEST(HostileScans, AGivenPoseRefusesTheSameBadScans) {
  const double inf = std::numeric_limits<double>::infinity();
  Scan huge = pointsOnly(sample().points);
  for (auto& p : huge.points) {
    p *= 1e7;
  }
  struct Case {
    const char* name;
    Scan scan;
    StatusCode code;
    const char* words;
  };
  const std::vector<Case> cases = {
      {"all inf", pointsOnly({{inf, 0, 0}, {0, -inf, 0}}), StatusCode::kInvalidInput, "no finite"},
      {"two points",
       pointsOnly({{0, 0, 0}, {0.05, 0.01, 0}}),
       StatusCode::kDegenerateInput,
       "2 finite points"},
      {"identical points",
       pointsOnly(Points(5000, Eigen::Vector3d(0.01, 0.02, 0.03))),
       StatusCode::kDegenerateInput,
       "collinear"},
      {"1e6 m", huge, StatusCode::kUnitsMismatch, "check the units"},
  };
  const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (const Case& c : cases) {
    expectRefused(inspectFrom(blade(), c.scan, pose, PipelineConfig()),
                  c.code,
                  c.words,
                  std::string(c.name) + ", refined");
    expectRefused(inspectAt(blade(), c.scan, pose, PipelineConfig()),
                  c.code,
                  c.words,
                  std::string(c.name) + ", fixed");
  }
  expectSampleStillRegisters();
}

TEST(HostileScans, HalfThePointsDuplicatedStillRegisters) {
  // Duplicates (a driver that sends a frame twice, overlapping views merged) must not break the
  // neighbourhoods: zero distances, repeated neighbours.
  Scan doubled = sample();
  doubled.normals.clear();
  const std::size_t half = doubled.points.size() / 2;
  for (std::size_t i = 0; i < half; ++i) {
    doubled.points.push_back(doubled.points[i]);
  }
  const InspectionResult result = inspect(blade(), doubled, PipelineConfig());
  EXPECT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.registration, RegistrationStatus::kOk) << result.status.message;
  EXPECT_EQ(result.counts.scan_points, sample().points.size() + half);
}

TEST(HostileScans, HugeCoordinatesAreAUnitsMismatchNeverANaNThatSlipsThrough) {
  struct Case {
    const char* name;
    double scale;
  };
  // The blade is 0.16 m across: 1e7 times larger gives 1.6e6 m; 1e30 and 1e300 overflow the
  // covariance (1e600 is inf in double), which must still be a refusal, not NaN passing checks.
  for (const Case& c : {Case{"1e6 m", 1e7}, Case{"1e30 m", 1e30}, Case{"1e300 m", 1e300}}) {
    Scan huge = pointsOnly(sample().points);
    for (auto& p : huge.points) {
      p *= c.scale;
    }
    expectRefused(inspect(blade(), huge, PipelineConfig()),
                  StatusCode::kUnitsMismatch,
                  "check the units",
                  c.name);
  }
  // One stray point at 1e30 m among a good scan dominates the covariance: refused as a line
  // whose spread (about 1e30 / sqrt(n) m) shows the absurd coordinate.
  Scan stray = pointsOnly(sample().points);
  stray.points.emplace_back(1e30, 0.0, 0.0);
  expectRefused(inspect(blade(), stray, PipelineConfig()),
                StatusCode::kDegenerateInput,
                "scan is collinear (principal spreads 5.773e+27",
                "stray point");
  expectSampleStillRegisters();
}

TEST(HostileScans, MorePointsThanTheCapAreRefusedNamingTheCap) {
  // A small cap instead of ten million points: the same check, without the allocation.
  PipelineConfig capped;
  capped.input.max_points = 1000;
  const InspectionResult result = inspect(blade(), sample(), capped);
  expectRefused(result,
                StatusCode::kInvalidInput,
                "scan has " + std::to_string(sample().points.size()) +
                    " points, more than input.max_points = 1000",
                "capped");
  EXPECT_EQ(result.timings.front().stage, "clean");
  expectSampleStillRegisters();
}

TEST(HostileScans, ScanInMillimetresAgainstCadInMetresThenTheGoodScan) {
  Scan in_mm = pointsOnly(sample().points);
  for (auto& p : in_mm.points) {
    p *= 1000.0;
  }
  expectRefused(inspect(blade(), in_mm, PipelineConfig()),
                StatusCode::kUnitsMismatch,
                "millimetres need scale 0.001",
                "scan in mm");
  expectSampleStillRegisters();
}

// ---------------------------------------------------------------- CAD ----

TEST(HostileCad, MillimetreCadLoadedAsMetresIsAUnitsMismatchAgainstAScanInMetres) {
  const std::string path = tempPath("box_mm.stl");
  ASSERT_TRUE(saveMeshStl(path, test::makeBox(kHalf), 1000.0).ok());     // 100 × 60 × 40 "units"
  const ModelLoadResult as_metres = loadModel(path, 1.0, "box");         // wrong: the file is in mm
  ASSERT_TRUE(as_metres.status.ok()) << as_metres.status.message;        // a 100 m part is legal
  const Scan scan = pointsOnly(test::sampleBoxSurface(kHalf, 2000, 3));  // metres
  expectRefused(inspect(*as_metres.model, scan, PipelineConfig()),
                StatusCode::kUnitsMismatch,
                "check the units of the scan and of the CAD",
                "mm CAD as m");
  const ModelLoadResult right = loadModel(path, *unitScale("mm"), "box");
  ASSERT_TRUE(right.status.ok()) << right.status.message;
  const InspectionResult result = inspect(*right.model, scan, PipelineConfig());
  EXPECT_NE(result.status.code, StatusCode::kUnitsMismatch) << result.status.message;
}

TEST(HostileCad, BinaryStlUnderstatingItsTriangleCountIsInvalid) {
  // The lie the other way round from io_stl_test's BinaryWithLyingCountNamesBothSizes: the file
  // holds twelve triangles but declares one; reading one would silently drop eleven faces.
  const std::string path = io_test::writeBytes(
      tempPath("understated.stl"), io_test::binaryStl(io_test::makeCube(1.0), "under", 1));
  const ModelLoadResult result = loadModel(path, 0.001, "cube");
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput) << result.status.message;
  EXPECT_TRUE(mentions(result.status.message, "declares 1 triangles (134 bytes)"));
  EXPECT_TRUE(mentions(result.status.message, "684 bytes"));
  EXPECT_FALSE(result.model);
}

TEST(HostileCad, NonManifoldCadLoadsWithAWarningNamingTheEdges) {
  // A closed cube with a fin: a third face on the edge 1-2 of the bottom.
  std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nv 2 0.5 -1\n"
      "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  const std::string closed_path = io_test::writeBytes(tempPath("cube.obj"), obj);
  const ModelLoadResult closed = loadModel(closed_path, 0.01, "cube");
  ASSERT_TRUE(closed.status.ok()) << closed.status.message;
  EXPECT_TRUE(closed.warnings.empty());
  obj += "f 2 3 9\n";
  const std::string path = io_test::writeBytes(tempPath("fin.obj"), obj);
  const ModelLoadResult fin = loadModel(path, 0.01, "fin");
  ASSERT_TRUE(fin.status.ok()) << fin.status.message;
  ASSERT_TRUE(fin.model);
  bool named = false;
  for (const std::string& warning : fin.warnings) {
    named = named || (mentions(warning, "1 non-manifold") && mentions(warning, "deviation signs"));
  }
  EXPECT_TRUE(named) << joinMessages(fin.warnings);
}

TEST(HostileCad, DegenerateFacesAreDroppedAndAllDegenerateIsRefused) {
  // One good triangle, one with a repeated corner, one collinear: the repeated corner is dropped
  // with a warning; the collinear face is kept with a zero normal (it has no area to match).
  const std::string mixed = io_test::writeBytes(
      tempPath("mixed.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 1 3\nf 1 2 4\n");
  const MeshLoadResult loaded = loadMesh(mixed, 1.0);
  ASSERT_TRUE(loaded.status.ok()) << loaded.status.message;
  EXPECT_EQ(loaded.file_faces, 3u);
  EXPECT_EQ(loaded.mesh.faces.size(), 2u);  // the collinear face stays, with a zero normal
  EXPECT_TRUE(mentions(joinMessages(loaded.warnings), "dropped 1 faces with a repeated vertex"));

  const std::string sliver =
      io_test::writeBytes(tempPath("sliver.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  const ModelLoadResult flat = loadModel(sliver, 1.0, "sliver");
  EXPECT_EQ(flat.status.code, StatusCode::kDegenerateInput) << flat.status.message;
  EXPECT_TRUE(mentions(flat.status.message, "'" + sliver + "' has zero surface area"));
  EXPECT_FALSE(flat.model);
}

TEST(HostileCad, ZeroExtentModelIsDegenerate) {
  const std::string point = io_test::writeBytes(
      tempPath("point.obj"), "v 1 1 1\nv 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\nf 1 3 4\n");
  const ModelLoadResult result = loadModel(point, 1.0, "point");
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput) << result.status.message;
  EXPECT_TRUE(mentions(result.status.message, "'" + point + "' has zero extent"));
  EXPECT_FALSE(result.model);
}

TEST(HostileCad, CorruptCadFilesLeaveTheLoadedModelServing) {
  // The node keeps its model when a load fails; here: failed loads do not disturb a model
  // loaded before them.
  const Model& model = blade();
  const TriangleMesh cube = io_test::makeCube(1.0);
  std::string truncated = io_test::binaryStl(cube, "cut");
  truncated.resize(truncated.size() - 20);
  const std::string cases[][2] = {
      {"missing.stl", ""},
      {"empty.ply", ""},
      {"cut.stl", truncated},
      {"bad.ply",
       "ply\nformat ascii 1.0\nelement vertex 1000\nproperty float x\nproperty float y"
       "\nproperty float z\nend_header\n0 0 0\n"},
      {"bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"},
  };
  for (const auto& c : cases) {
    const std::string path = tempPath(c[0]);
    std::filesystem::remove(path);
    if (std::string(c[0]) != "missing.stl") {
      io_test::writeBytes(path, c[1]);
    }
    const ModelLoadResult result = loadModel(path, 0.001, c[0]);
    EXPECT_EQ(result.status.code, StatusCode::kInvalidInput)
        << c[0] << ": " << result.status.message;
    EXPECT_TRUE(mentions(result.status.message, path)) << c[0];
    EXPECT_FALSE(result.model) << c[0];
  }
  EXPECT_EQ(model.id(), "blade");
  expectSampleStillRegisters();
}

}  // namespace
}  // namespace freeform_inspection
