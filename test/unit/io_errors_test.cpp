// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <cmath>
#include <limits>
#include <string>

#include "io_test_util.h"
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"

// Failures every loader shares: files that cannot be read, unknown formats, bad scales.

namespace freeform_inspection {
namespace {

using io_test::mentions;

class IoErrorTest : public ::testing::Test {
 protected:
  io_test::TempDir dir_;
};

TEST_F(IoErrorTest, MissingFile) {
  const std::string path = dir_.file("absent.stl");
  const MeshLoadResult mesh = loadMesh(path, 1.0);
  EXPECT_EQ(mesh.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(mesh.status.message, "cannot open '" + path + "': No such file"));
  const ScanLoadResult scan = loadScan(dir_.file("absent.pcd"), 1.0);
  EXPECT_EQ(scan.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(scan.status.message, "No such file"));
}

TEST_F(IoErrorTest, EmptyFileForEveryFormat) {
  for (const char* name : {"e.stl", "e.ply", "e.obj", "e.pcd"}) {
    const std::string path = io_test::writeBytes(dir_.file(name), "");
    const ScanLoadResult scan = loadScan(path, 1.0);
    EXPECT_EQ(scan.status.code, StatusCode::kInvalidInput) << name;
    EXPECT_TRUE(mentions(scan.status.message, "'" + path + "' is empty (0 bytes)"));
  }
  const MeshLoadResult mesh = loadMesh(io_test::writeBytes(dir_.file("e.stl"), ""), 1.0);
  EXPECT_EQ(mesh.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(mesh.status.message, "is empty"));
}

TEST_F(IoErrorTest, DirectoryInsteadOfFile) {
  const std::string path = dir_.file("folder.ply");
  std::filesystem::create_directory(path);
  const MeshLoadResult mesh = loadMesh(path, 1.0);
  EXPECT_EQ(mesh.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(mesh.status.message, "cannot open '" + path + "': Is a directory"));
  const ScanLoadResult scan = loadScan(path, 1.0);
  EXPECT_EQ(scan.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(scan.status.message, "Is a directory"));
}

TEST_F(IoErrorTest, UnknownExtension) {
  const std::string path = io_test::writeBytes(dir_.file("model.step"), "ISO-10303-21;");
  const MeshLoadResult mesh = loadMesh(path, 1.0);
  EXPECT_EQ(mesh.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(mesh.status.message, "unsupported extension '.step'"));
  EXPECT_TRUE(mentions(mesh.status.message, ".stl, .ply or .obj"));

  const ScanLoadResult none = loadScan(io_test::writeBytes(dir_.file("noext"), "x"), 1.0);
  EXPECT_EQ(none.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(none.status.message, "unsupported extension ''"));
}

TEST_F(IoErrorTest, PcdIsNotACadFormat) {
  const MeshLoadResult mesh = loadMesh(io_test::writeBytes(dir_.file("c.pcd"), "x"), 1.0);
  EXPECT_EQ(mesh.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(mesh.status.message, "unsupported extension '.pcd'"));
}

TEST_F(IoErrorTest, BadScales) {
  const std::string path = io_test::writeBytes(dir_.file("cube.stl"),
                                               io_test::binaryStl(io_test::makeCube(1.0), "cube"));
  struct Case {
    double scale;
    const char* text;
  };
  const Case cases[] = {{0.0, "got 0"},
                        {-0.001, "got -0.001"},
                        {std::nan(""), "got nan"},
                        {std::numeric_limits<double>::infinity(), "got inf"}};
  for (const Case& c : cases) {
    const MeshLoadResult mesh = loadMesh(path, c.scale);
    EXPECT_EQ(mesh.status.code, StatusCode::kInvalidInput) << c.text;
    EXPECT_TRUE(mentions(mesh.status.message, "scale must be finite and > 0"));
    EXPECT_TRUE(mentions(mesh.status.message, c.text));
    const ScanLoadResult scan = loadScan(path, c.scale);
    EXPECT_EQ(scan.status.code, StatusCode::kInvalidInput) << c.text;
    EXPECT_TRUE(mentions(scan.status.message, c.text));
  }
}

}  // namespace
}  // namespace freeform_inspection
