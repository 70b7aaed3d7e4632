// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "test_shapes.h"
#include <gtest/gtest.h>
#include <unistd.h>

#include "freeform_inspection/mesh.h"
#include "freeform_inspection/types.h"

/// Fixtures for the loader tests: a per-test temporary directory and byte-level writers of STL
/// and PLY that share no code with the library, so the readers are not only checked against
/// our own writers.
namespace freeform_inspection::io_test {

/// A fresh directory per test, removed when the test ends.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string("ffi_io_") + info->test_suite_name() + "_" + info->name() + "_" +
                       std::to_string(::getpid());
    std::replace(name.begin(), name.end(), '/', '_');  // parameterized test names
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

inline std::string writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  EXPECT_TRUE(out.good()) << path;
  return path;
}

inline std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Appends `value` in little-endian (or, with big_endian, big-endian) byte order.
template <typename T>
void put(std::string* out, T value, bool big_endian = false) {
  char buffer[sizeof(T)];
  std::memcpy(buffer, &value, sizeof(T));
  if (big_endian == (__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__)) {
    std::reverse(buffer, buffer + sizeof(T));
  }
  out->append(buffer, sizeof(T));
}

/// Cube [0, size]^3, 8 vertices, 12 triangles wound outward.
inline TriangleMesh makeCube(double size) {
  TriangleMesh mesh = test::makeBox(Eigen::Vector3d::Constant(size / 2));
  for (auto& v : mesh.vertices) {
    v += Eigen::Vector3d::Constant(size / 2);
  }
  mesh.face_normals = computeFaceNormals(mesh.vertices, mesh.faces);
  return mesh;
}

/// The same cube as 6 counter-clockwise quads (for fan triangulation).
inline std::vector<std::vector<int>> cubeQuads() {
  return {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
}

/// Regular tetrahedron with corners (±1, ±1, ±1) (even sign count), times `size`, wound
/// outward: edge 2√2·size, volume 8/3·size³, area 8√3·size².
inline TriangleMesh makeTetrahedron(double size) {
  TriangleMesh mesh;
  mesh.vertices = {Eigen::Vector3d(1, 1, 1) * size,
                   Eigen::Vector3d(1, -1, -1) * size,
                   Eigen::Vector3d(-1, 1, -1) * size,
                   Eigen::Vector3d(-1, -1, 1) * size};
  mesh.faces = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};
  mesh.face_normals = computeFaceNormals(mesh.vertices, mesh.faces);
  return mesh;
}

inline std::vector<std::vector<int>> toPolygons(const Triangles& faces) {
  std::vector<std::vector<int>> polygons;
  for (const auto& f : faces) {
    polygons.push_back({f[0], f[1], f[2]});
  }
  return polygons;
}

/// Ascii STL, written like a typical CAD exporter (indented, normals zero).
inline std::string asciiStl(const TriangleMesh& mesh) {
  std::string text = "solid test\n";
  for (const auto& f : mesh.faces) {
    text += "  facet normal 0 0 0\n    outer loop\n";
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& v = mesh.vertices[static_cast<std::size_t>(f[c])];
      text += "      vertex " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " +
              std::to_string(v.z()) + "\n";
    }
    text += "    endloop\n  endfacet\n";
  }
  return text + "endsolid test\n";
}

/// Binary STL; `header` fills the start of the 80-byte header, `count` overrides the count.
inline std::string binaryStl(const TriangleMesh& mesh,
                             const std::string& header,
                             std::int64_t count = -1) {
  std::string bytes = header;
  bytes.resize(80, ' ');
  put(&bytes,
      static_cast<std::uint32_t>(count < 0 ? static_cast<std::int64_t>(mesh.faces.size()) : count));
  for (const auto& f : mesh.faces) {
    for (int i = 0; i < 3; ++i) {
      put(&bytes, 0.0f);
    }
    for (int c = 0; c < 3; ++c) {
      for (int i = 0; i < 3; ++i) {
        put(&bytes, static_cast<float>(mesh.vertices[static_cast<std::size_t>(f[c])][i]));
      }
    }
    put(&bytes, std::uint16_t{0});
  }
  return bytes;
}

enum class PlyEncoding { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

/// A PLY mesh or cloud: float or double x y z, optional polygons as `list uchar int`.
inline std::string plyBytes(const Points& vertices,
                            const std::vector<std::vector<int>>& polygons,
                            PlyEncoding encoding,
                            bool double_coordinates,
                            bool with_face_element = true) {
  const bool binary = encoding != PlyEncoding::kAscii;
  const bool big = encoding == PlyEncoding::kBinaryBigEndian;
  const char* type = double_coordinates ? "double" : "float";
  std::string text = "ply\nformat ";
  text += encoding == PlyEncoding::kAscii                ? "ascii"
          : encoding == PlyEncoding::kBinaryLittleEndian ? "binary_little_endian"
                                                         : "binary_big_endian";
  text += " 1.0\ncomment hand-written test fixture\nobj_info nothing\n";
  text += "element vertex " + std::to_string(vertices.size()) + "\n";
  for (const char* axis : {"x", "y", "z"}) {
    text += std::string("property ") + type + " " + axis + "\n";
  }
  if (with_face_element) {
    text += "element face " + std::to_string(polygons.size()) +
            "\nproperty list uchar int vertex_indices\n";
  }
  text += "end_header\n";
  for (const auto& v : vertices) {
    for (int i = 0; i < 3; ++i) {
      if (!binary) {
        char buffer[64];
        std::snprintf(buffer, sizeof(buffer), "%.17g ", v[i]);
        text += buffer;
      } else if (double_coordinates) {
        put(&text, v[i], big);
      } else {
        put(&text, static_cast<float>(v[i]), big);
      }
    }
    if (!binary) {
      text += "\n";
    }
  }
  for (const auto& polygon : polygons) {
    if (binary) {
      put(&text, static_cast<std::uint8_t>(polygon.size()), big);
    } else {
      text += std::to_string(polygon.size());
    }
    for (const int index : polygon) {
      if (binary) {
        put(&text, static_cast<std::int32_t>(index), big);
      } else {
        text += " " + std::to_string(index);
      }
    }
    if (!binary) {
      text += "\n";
    }
  }
  return text;
}

/// Every face normal is unit length and points away from the vertex centroid.
inline void expectOutwardNormals(const TriangleMesh& mesh) {
  ASSERT_EQ(mesh.face_normals.size(), mesh.faces.size());
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& v : mesh.vertices) {
    centroid += v / static_cast<double>(mesh.vertices.size());
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    const Eigen::Vector3d center = (mesh.vertices[static_cast<std::size_t>(face[0])] +
                                    mesh.vertices[static_cast<std::size_t>(face[1])] +
                                    mesh.vertices[static_cast<std::size_t>(face[2])]) /
                                   3.0;
    EXPECT_NEAR(mesh.face_normals[f].norm(), 1.0, 1e-12) << "face " << f;
    EXPECT_GT(mesh.face_normals[f].dot(center - centroid), 0.0) << "face " << f;
  }
}

/// Checks a loaded 10 mm cube read with scale 0.001: closed, outward, 1 cm³.
inline void expectCentimetreCube(const TriangleMesh& mesh) {
  EXPECT_EQ(mesh.vertices.size(), 8u);
  EXPECT_EQ(mesh.faces.size(), 12u);
  const BoundingBox box = computeBoundingBox(mesh.vertices);
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(box.min[i], 0.0);
    EXPECT_DOUBLE_EQ(box.max[i], 0.01);
  }
  const MeshTopology topology = analyzeTopology(mesh);
  EXPECT_TRUE(topology.isOutwardSolid());
  EXPECT_NEAR(topology.signed_volume, 1e-6, 1e-18);
  EXPECT_NEAR(topology.area, 6e-4, 1e-16);
  expectOutwardNormals(mesh);
}

/// True when `text` contains `part` (for message checks with a readable failure).
inline ::testing::AssertionResult mentions(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "'" << text << "' does not mention '" << part << "'";
}

}  // namespace freeform_inspection::io_test
