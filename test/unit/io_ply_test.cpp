// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <string>

#include "io_test_util.h"
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

using io_test::mentions;
using io_test::PlyEncoding;

class PlyTest : public ::testing::Test {
 protected:
  MeshLoadResult loadText(const std::string& text) {
    return loadMesh(io_test::writeBytes(dir_.file("mesh.ply"), text), 1.0);
  }

  io_test::TempDir dir_;
};

struct PlyCase {
  const char* name;
  PlyEncoding encoding;
  bool double_coordinates;
};

class PlyEncodingTest : public PlyTest, public ::testing::WithParamInterface<PlyCase> {};

TEST_P(PlyEncodingTest, CubeInMillimetres) {
  const TriangleMesh cube = io_test::makeCube(10.0);
  const std::string bytes = io_test::plyBytes(cube.vertices,
                                              io_test::toPolygons(cube.faces),
                                              GetParam().encoding,
                                              GetParam().double_coordinates);
  const MeshLoadResult result = loadMesh(io_test::writeBytes(dir_.file("cube.ply"), bytes), 0.001);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_vertices, 8u);
  EXPECT_EQ(result.file_faces, 12u);
  EXPECT_TRUE(result.warnings.empty());
  io_test::expectCentimetreCube(result.mesh);
}

TEST_P(PlyEncodingTest, TetrahedronAsScan) {
  const TriangleMesh tetra = io_test::makeTetrahedron(2.0);
  const std::string bytes = io_test::plyBytes(tetra.vertices,
                                              io_test::toPolygons(tetra.faces),
                                              GetParam().encoding,
                                              GetParam().double_coordinates);
  const ScanLoadResult result = loadScan(io_test::writeBytes(dir_.file("t.ply"), bytes), 1.0);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_points, 4u);
  EXPECT_EQ(result.non_finite_removed, 0u);
  ASSERT_EQ(result.scan.points.size(), 4u);
  EXPECT_EQ(result.scan.points[1], Eigen::Vector3d(2, -2, -2));
  EXPECT_EQ(result.scan.faces, tetra.faces);
  EXPECT_TRUE(result.scan.normals.empty());
}

INSTANTIATE_TEST_SUITE_P(
    Encodings,
    PlyEncodingTest,
    ::testing::Values(PlyCase{"AsciiFloat", PlyEncoding::kAscii, false},
                      PlyCase{"BinaryLittleEndianFloat", PlyEncoding::kBinaryLittleEndian, false},
                      PlyCase{"BinaryLittleEndianDouble", PlyEncoding::kBinaryLittleEndian, true},
                      PlyCase{"BinaryBigEndianFloat", PlyEncoding::kBinaryBigEndian, false},
                      PlyCase{"BinaryBigEndianDouble", PlyEncoding::kBinaryBigEndian, true}),
    [](const ::testing::TestParamInfo<PlyCase>& info) { return std::string(info.param.name); });

TEST_F(PlyTest, DoubleCoordinatesKeepTheirPrecision) {
  // 1000.000001 is not representable in float (spacing 6e-5 there): a float path would lose it.
  const Points points = {{1000.000001, -2000.0000003, 0.1}, {1, 2, 3}};
  for (const auto encoding :
       {PlyEncoding::kAscii, PlyEncoding::kBinaryLittleEndian, PlyEncoding::kBinaryBigEndian}) {
    const ScanLoadResult result = loadScan(
        io_test::writeBytes(dir_.file("p.ply"), io_test::plyBytes(points, {}, encoding, true)),
        1.0);
    ASSERT_TRUE(result.status.ok()) << result.status.message;
    ASSERT_EQ(result.scan.points.size(), 2u);
    EXPECT_EQ(result.scan.points[0], points[0]);
  }
}

TEST_F(PlyTest, QuadsAreTriangulatedAsFans) {
  const TriangleMesh cube = io_test::makeCube(10.0);
  for (const auto encoding : {PlyEncoding::kAscii, PlyEncoding::kBinaryLittleEndian}) {
    const MeshLoadResult result =
        loadMesh(io_test::writeBytes(
                     dir_.file("quads.ply"),
                     io_test::plyBytes(cube.vertices, io_test::cubeQuads(), encoding, false)),
                 0.001);
    ASSERT_TRUE(result.status.ok()) << result.status.message;
    EXPECT_EQ(result.file_faces, 6u);
    EXPECT_EQ(result.mesh.faces[0], Eigen::Vector3i(0, 2, 3));
    EXPECT_EQ(result.mesh.faces[1], Eigen::Vector3i(0, 3, 1));
    io_test::expectCentimetreCube(result.mesh);
  }
}

TEST_F(PlyTest, AllTypeNamesAndExtraPropertiesAreRead) {
  const std::string text =
      "ply\nformat ascii 1.0\n"
      "element vertex 3\n"
      "property int8 a\nproperty uint8 b\nproperty short c\nproperty ushort d\n"
      "property float64 x\nproperty float32 y\nproperty int32 z\nproperty uint e\n"
      "property uchar red\n"
      "element face 1\nproperty uint16 flags\nproperty list char uint vertex_index\n"
      "end_header\n"
      "-1 2 -3 4 0 0 0 5 255\n"
      "-1 2 -3 4 1 0 0 5 255\n"
      "-1 2 -3 4 0 1 7 5 255\n"
      "9 3 0 1 2\n";
  const MeshLoadResult result = loadText(text);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.mesh.vertices.size(), 3u);
  EXPECT_EQ(result.mesh.vertices[2], Eigen::Vector3d(0, 1, 7));
  ASSERT_EQ(result.mesh.faces.size(), 1u);
  EXPECT_EQ(result.mesh.face_normals[0], Eigen::Vector3d(0, -7, 1).normalized());
}

// Scanners (Stanford range data) store a range_grid element with list properties.
std::string rangeGridCloud(bool binary) {
  std::string text = std::string("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") +
                     " 1.0\nobj_info num_cols 2\nobj_info num_rows 2\n"
                     "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "property float confidence\n"
                     "element range_grid 4\nproperty list uchar int vertex_indices\n"
                     "end_header\n";
  const float values[3][4] = {{1, 2, 3, 0.5f}, {4, 5, 6, 0.5f}, {7, 8, 9, 1}};
  const std::vector<std::vector<int>> grid = {{0}, {}, {1, 2}, {2}};
  for (const auto& row : values) {
    for (const float v : row) {
      if (binary) {
        io_test::put(&text, v);
      } else {
        text += std::to_string(v) + " ";
      }
    }
    text += binary ? "" : "\n";
  }
  for (const auto& cell : grid) {
    if (binary) {
      io_test::put(&text, static_cast<std::uint8_t>(cell.size()));
    } else {
      text += std::to_string(cell.size());
    }
    for (const int index : cell) {
      if (binary) {
        io_test::put(&text, static_cast<std::int32_t>(index));
      } else {
        text += " " + std::to_string(index);
      }
    }
    text += binary ? "" : "\n";
  }
  return text;
}

TEST_F(PlyTest, RangeGridElementIsSkipped) {
  for (const bool binary : {false, true}) {
    const ScanLoadResult result =
        loadScan(io_test::writeBytes(dir_.file("grid.ply"), rangeGridCloud(binary)), 0.001);
    ASSERT_TRUE(result.status.ok()) << result.status.message;
    ASSERT_EQ(result.scan.points.size(), 3u);
    EXPECT_TRUE(result.scan.faces.empty());
    EXPECT_DOUBLE_EQ(result.scan.points[2].z(), 0.009);
    EXPECT_TRUE(result.warnings.empty()) << result.warnings.front();
  }
}

TEST_F(PlyTest, RangeGridCloudAsCadIsDegenerate) {
  const MeshLoadResult result =
      loadMesh(io_test::writeBytes(dir_.file("grid.ply"), rangeGridCloud(true)), 0.001);
  EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput);
  EXPECT_TRUE(mentions(result.status.message, "has no faces: a CAD model must be a triangle mesh"));
}

TEST_F(PlyTest, ScanNormalsAreReadAndNormalized) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty double y\n"
      "property double z\nproperty float nx\nproperty float ny\nproperty float nz\nend_header\n"
      "0 0 0 0 0 2\n1 0 0 3 4 0\n";
  const ScanLoadResult result = loadScan(io_test::writeBytes(dir_.file("n.ply"), text), 1.0);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.scan.normals.size(), 2u);
  EXPECT_EQ(result.scan.normals[0], Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(result.scan.normals[1], Eigen::Vector3d(0.6, 0.8, 0));
}

TEST_F(PlyTest, FaceIndexOutOfRange) {
  const MeshLoadResult result = loadText(
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "face 0 references vertex 3"));
  EXPECT_TRUE(mentions(result.status.message, "3 vertices"));

  const Points v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const MeshLoadResult negative =
      loadMesh(io_test::writeBytes(
                   dir_.file("neg.ply"),
                   io_test::plyBytes(v, {{0, -1, 2}}, PlyEncoding::kBinaryLittleEndian, false)),
               1.0);
  EXPECT_EQ(negative.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(negative.status.message, "references vertex -1"));
}

TEST_F(PlyTest, TruncatedBinary) {
  const TriangleMesh cube = io_test::makeCube(1.0);
  std::string bytes = io_test::plyBytes(
      cube.vertices, io_test::toPolygons(cube.faces), PlyEncoding::kBinaryLittleEndian, true);
  bytes.resize(bytes.size() - 7);  // inside the last face
  const MeshLoadResult result = loadMesh(io_test::writeBytes(dir_.file("cut.ply"), bytes), 1.0);
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "element 'face' record 11"));
  EXPECT_TRUE(mentions(result.status.message, "truncated"));

  bytes.resize(bytes.size() - 13 * 11 - 20);  // inside the vertices
  const MeshLoadResult in_vertices =
      loadMesh(io_test::writeBytes(dir_.file("cut.ply"), bytes), 1.0);
  EXPECT_EQ(in_vertices.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(in_vertices.status.message, "element 'vertex' declares 8 records"));
}

TEST_F(PlyTest, VertexCountLargerThanDataFailsBeforeAllocating) {
  const std::string text =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1000\n"
      "property double x\nproperty double y\nproperty double z\nend_header\n" +
      std::string(48, '\0');
  const MeshLoadResult result = loadText(text);
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message,
                       "element 'vertex' declares 1000 records of at least 24 bytes"));
  EXPECT_TRUE(mentions(result.status.message, "only 48 bytes"));

  std::string huge = text;
  huge.replace(huge.find("1000"), 4, "4000000000000");
  const MeshLoadResult too_many = loadText(huge);
  EXPECT_EQ(too_many.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(too_many.status.message, "too many vertices (4000000000000)"));

  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 0 0\n1 1 1\n";
  const ScanLoadResult scan = loadScan(io_test::writeBytes(dir_.file("a.ply"), ascii), 1.0);
  EXPECT_EQ(scan.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(scan.status.message, "declares 5 records"));
}

TEST_F(PlyTest, NegativeAndAbsurdListCounts) {
  const std::string head =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list int int vertex_indices\nend_header\n";
  std::string body;
  for (int i = 0; i < 9; ++i) {
    io_test::put(&body, static_cast<float>(i));
  }
  std::string negative = head + body;
  io_test::put(&negative, std::int32_t{-3});
  negative += std::string(12, '\0');
  const MeshLoadResult neg = loadText(negative);
  EXPECT_EQ(neg.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(neg.status.message, "negative list count -3"));

  std::string absurd = head + body;
  io_test::put(&absurd, std::int32_t{2000000000});
  absurd += std::string(12, '\0');
  const MeshLoadResult big = loadText(absurd);
  EXPECT_EQ(big.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(big.status.message, "list count 2000000000"));
}

TEST_F(PlyTest, BadHeaders) {
  struct Case {
    std::string text;
    std::string expected;
  };
  const std::string vertex =
      "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
  const Case cases[] = {
      {"plx\nformat ascii 1.0\n", "not a PLY file"},
      {"ply\nformat ascii 1.0\n" + vertex, "no end_header"},
      {"ply\nformat ascii 1.0\n" + vertex + "0 0 0\n", "line 7: unexpected '0'"},
      {"ply\nformat binary_middle_endian 1.0\n" + vertex + "end_header\n",
       "unknown PLY format 'binary_middle_endian'"},
      {"ply\nformat ascii 2.0\n" + vertex + "end_header\n", "unsupported PLY version '2.0'"},
      {"ply\n" + vertex + "end_header\n0 0 0\n", "no 'format' line"},
      {"ply\nformat ascii 1.0\nelement vertex -4\nend_header\n", "count >= 0"},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "property before any element"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\nend_header\n",
       "unknown PLY type 'half'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n",
       "list count type must be an integer"},
      {"ply\nformat ascii 1.0\nbogus line\n", "line 3: unexpected 'bogus'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
       "end_header\n0 0\n",
       "vertex element has no 'z' property"},
      {"ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\n"
       "end_header\n",
       "expected one 'vertex' element"},
      {"ply\nformat ascii 1.0\n" + vertex + "element face 1\nproperty int vertex_indices\n" +
           "end_header\n0 0 0\n0\n",
       "no 'vertex_indices' list"},
      {"ply\nformat ascii 1.0\n" + vertex + "end_header\n0 zero 0\n", "bad number 'zero'"},
  };
  for (const Case& c : cases) {
    const MeshLoadResult result = loadText(c.text);
    EXPECT_EQ(result.status.code, StatusCode::kInvalidInput) << c.text;
    EXPECT_TRUE(mentions(result.status.message, c.expected));
  }
}

TEST_F(PlyTest, FacelessPlyIsNotACadModel) {
  const Points points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (const bool face_element : {false, true}) {
    const std::string path = io_test::writeBytes(
        dir_.file("cloud.ply"),
        io_test::plyBytes(points, {}, PlyEncoding::kBinaryLittleEndian, false, face_element));
    const MeshLoadResult result = loadMesh(path, 1.0);
    EXPECT_EQ(result.status.code, StatusCode::kDegenerateInput);
    EXPECT_TRUE(mentions(result.status.message, "'" + path + "' has no faces"));
    EXPECT_TRUE(loadScan(path, 1.0).status.ok());
  }
}

TEST_F(PlyTest, RepeatedIndexAndShortFacesAreDroppedWithWarnings) {
  const TriangleMesh cube = io_test::makeCube(1.0);
  auto polygons = io_test::toPolygons(cube.faces);
  polygons.push_back({0, 1, 1});
  polygons.push_back({0, 1});
  const MeshLoadResult result = loadMesh(
      io_test::writeBytes(dir_.file("d.ply"),
                          io_test::plyBytes(cube.vertices, polygons, PlyEncoding::kAscii, false)),
      1.0);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.file_faces, 14u);
  EXPECT_EQ(result.mesh.faces.size(), 12u);
  ASSERT_EQ(result.warnings.size(), 2u);
  EXPECT_TRUE(mentions(result.warnings[0], "fewer than 3 vertices"));
  EXPECT_TRUE(mentions(result.warnings[1], "repeated vertex index"));
}

TEST_F(PlyTest, NonFiniteCadVertexIsInvalid) {
  const Points v = {{0, 0, 0}, {1, 0, 0}, {0, std::nan(""), 0}};
  const MeshLoadResult result =
      loadMesh(io_test::writeBytes(
                   dir_.file("nan.ply"),
                   io_test::plyBytes(v, {{0, 1, 2}}, PlyEncoding::kBinaryLittleEndian, false)),
               1.0);
  EXPECT_EQ(result.status.code, StatusCode::kInvalidInput);
  EXPECT_TRUE(mentions(result.status.message, "vertex 2 is not finite"));
}

}  // namespace
}  // namespace freeform_inspection
