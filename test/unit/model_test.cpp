// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/model.h"

#include <cmath>
#include <filesystem>
#include <string>

#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"

namespace freeform_inspection {
namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::path(::testing::TempDir()) / ("model_test_" + name)).string();
}

TEST(UnitScale, KnowsMetresMillimetresInchesAndNothingElse) {
  EXPECT_EQ(unitScale("m").value(), 1.0);
  EXPECT_EQ(unitScale("mm").value(), 0.001);
  EXPECT_EQ(unitScale("in").value(), 0.0254);
  EXPECT_FALSE(unitScale("MM"));
  EXPECT_FALSE(unitScale(""));
  EXPECT_FALSE(unitScale("cm"));
}

TEST(LoadModel, ReadsMillimetreFileIntoMetres) {
  const std::string path = tempPath("box_mm.stl");
  // A 40 × 20 × 10 mm box written in millimetres, as CAD files usually are.
  ASSERT_TRUE(saveMeshStl(path, test::makeBox({0.02, 0.01, 0.005}), 1000.0).ok());
  const ModelLoadResult loaded = loadModel(path, 0.001, "box");
  ASSERT_TRUE(loaded.status.ok()) << loaded.status.message;
  const Model& model = *loaded.model;
  EXPECT_EQ(model.id(), "box");
  EXPECT_EQ(model.source(), path);
  EXPECT_EQ(model.mesh().vertices.size(), 8u);
  EXPECT_EQ(model.mesh().faces.size(), 12u);
  EXPECT_NEAR(model.bounds().extent().x(), 0.04, 1e-9);
  EXPECT_NEAR(model.bounds().extent().y(), 0.02, 1e-9);
  EXPECT_NEAR(model.bounds().extent().z(), 0.01, 1e-9);
  EXPECT_TRUE(model.topology().isOutwardSolid());
  EXPECT_NEAR(model.topology().signed_volume, 0.04 * 0.02 * 0.01, 1e-12);
  EXPECT_TRUE(loaded.warnings.empty());
}

TEST(LoadModel, OpenMeshLoadsWithAWarningAboutSigns) {
  TriangleMesh open_box = test::makeBox({1, 1, 1});
  open_box.faces.pop_back();
  const std::string path = tempPath("open.stl");
  ASSERT_TRUE(saveMeshStl(path, open_box).ok());
  const ModelLoadResult loaded = loadModel(path, 1.0, "open");
  ASSERT_TRUE(loaded.status.ok()) << loaded.status.message;
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("3 boundary"), std::string::npos) << loaded.warnings[0];
}

TEST(LoadModel, MissingFileIsInvalidInputNamingThePath) {
  const ModelLoadResult loaded = loadModel("/nonexistent/dir/part.stl", 0.001, "x");
  EXPECT_EQ(loaded.status.code, StatusCode::kInvalidInput);
  EXPECT_NE(loaded.status.message.find("/nonexistent/dir/part.stl"), std::string::npos);
  EXPECT_FALSE(loaded.model);
}

TEST(LoadModel, FlatZeroVolumeStillNeedsAreaAndAllDegenerateFacesAreRefused) {
  TriangleMesh sliver;
  sliver.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};  // collinear: zero area
  sliver.faces = {{0, 1, 2}};
  const std::string path = tempPath("sliver.stl");
  ASSERT_TRUE(saveMeshStl(path, sliver).ok());
  const ModelLoadResult loaded = loadModel(path, 1.0, "sliver");
  EXPECT_FALSE(loaded.status.ok());
  EXPECT_EQ(loaded.status.code, StatusCode::kDegenerateInput) << loaded.status.message;
}

}  // namespace
}  // namespace freeform_inspection
