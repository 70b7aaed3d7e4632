// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <random>
#include <string>
#include <vector>

#include "io_test_util.h"
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"

// Every prefix and many corruptions of valid files must give a Status, never a crash, a hang
// or an out-of-bounds read (run under AddressSanitizer to make the last one visible).

namespace freeform_inspection {
namespace {

using io_test::PlyEncoding;

struct Sample {
  const char* name;
  std::string bytes;
};

std::vector<Sample> samples() {
  const TriangleMesh cube = io_test::makeCube(10.0);
  return {
      {"a.stl", io_test::asciiStl(cube)},
      {"b.stl", io_test::binaryStl(cube, "solid looking")},
      {"a.ply", io_test::plyBytes(cube.vertices, io_test::cubeQuads(), PlyEncoding::kAscii, false)},
      {"le.ply",
       io_test::plyBytes(
           cube.vertices, io_test::cubeQuads(), PlyEncoding::kBinaryLittleEndian, true)},
      {"be.ply",
       io_test::plyBytes(
           cube.vertices, io_test::cubeQuads(), PlyEncoding::kBinaryBigEndian, false)},
      {"m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1/1 2/2 4/3 3/4\nf -4 -3 -2\n"},
  };
}

bool acceptable(StatusCode code) {
  return code == StatusCode::kOk || code == StatusCode::kInvalidInput ||
         code == StatusCode::kDegenerateInput;
}

class RobustnessTest : public ::testing::Test {
 protected:
  void loadBoth(const std::string& name, const std::string& bytes) {
    const std::string path = io_test::writeBytes(dir_.file(name), bytes);
    const MeshLoadResult mesh = loadMesh(path, 0.001);
    EXPECT_TRUE(acceptable(mesh.status.code)) << name << ": " << mesh.status.message;
    EXPECT_TRUE(mesh.status.ok() || !mesh.status.message.empty());
    const ScanLoadResult scan = loadScan(path, 0.001);
    EXPECT_TRUE(acceptable(scan.status.code)) << name << ": " << scan.status.message;
  }

  io_test::TempDir dir_;
};

TEST_F(RobustnessTest, EveryTruncation) {
  for (const Sample& sample : samples()) {
    for (std::size_t size = 1; size < sample.bytes.size(); ++size) {
      loadBoth(sample.name, sample.bytes.substr(0, size));
    }
  }
}

TEST_F(RobustnessTest, RandomByteCorruption) {
  std::mt19937 rng(42);
  for (const Sample& sample : samples()) {
    std::uniform_int_distribution<std::size_t> position(0, sample.bytes.size() - 1);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int trial = 0; trial < 150; ++trial) {
      std::string bytes = sample.bytes;
      for (int k = 0; k < 1 + trial % 4; ++k) {
        bytes[position(rng)] = static_cast<char>(byte(rng));
      }
      loadBoth(sample.name, bytes);
    }
  }
}

}  // namespace
}  // namespace freeform_inspection
