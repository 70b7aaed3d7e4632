// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/organized_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include "analytic_clouds.h"
#include <gtest/gtest.h>

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

MeshTopology topologyOf(const Points& points, const Triangles& faces) {
  TriangleMesh mesh;
  mesh.vertices = points;
  mesh.faces = faces;
  return analyzeTopology(mesh);
}

// Every face: finite corners, and its right-hand normal towards the sensor at the origin.
void expectFacesFiniteAndFacingTheSensor(const Points& points, const Triangles& faces) {
  for (const auto& face : faces) {
    const Eigen::Vector3d& a = points[std::size_t(face[0])];
    const Eigen::Vector3d& b = points[std::size_t(face[1])];
    const Eigen::Vector3d& c = points[std::size_t(face[2])];
    ASSERT_TRUE(a.allFinite() && b.allFinite() && c.allFinite()) << face.transpose();
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    EXPECT_GT(normal.dot(-(a + b + c) / 3.0), 0.0) << face.transpose();
  }
}

bool nearNan(const analytic::OrganizedCloud& cloud, int row, int column, int reach) {
  for (int r = std::max(0, row - reach); r <= std::min(cloud.height - 1, row + reach); ++r) {
    for (int c = std::max(0, column - reach); c <= std::min(cloud.width - 1, column + reach); ++c) {
      if (!cloud.points[std::size_t(r * cloud.width + c)].allFinite()) {
        return true;
      }
    }
  }
  return false;
}

Triangles triangulate(const analytic::OrganizedCloud& cloud) {
  return triangulateOrganizedGrid(cloud.points, cloud.width, cloud.height, OrganizedMeshConfig());
}

TEST(OrganizedMesh, SphereSilhouetteGivesAnOrientedManifoldWithBoundary) {
  const analytic::Pinhole camera{64, 48, 60.0};
  const analytic::OrganizedCloud sphere =
      analytic::organizedSphere(camera, Eigen::Vector3d(0.05, -0.02, 1.0), 0.3);
  const Triangles faces = triangulate(sphere);
  ASSERT_FALSE(faces.empty());
  expectFacesFiniteAndFacingTheSensor(sphere.points, faces);
  const MeshTopology topology = topologyOf(sphere.points, faces);
  EXPECT_EQ(topology.non_manifold_edges, 0u);
  EXPECT_EQ(topology.misoriented_edges, 0u);
  EXPECT_EQ(topology.degenerate_faces, 0u);
  EXPECT_GT(topology.boundary_edges, 0u);
  // NaN pixels are unused. So are a few finite ones on the rim, where the sphere is seen at a
  // grazing angle and the depth step exceeds 5 × the median edge (5 of 1121 here): no finite
  // pixel away from the silhouette may be left out.
  std::vector<char> used(sphere.points.size(), 0);
  for (const auto& face : faces) {
    for (int c = 0; c < 3; ++c) {
      used[std::size_t(face[c])] = 1;
    }
  }
  std::size_t unused_finite = 0;
  for (int row = 0; row < camera.height; ++row) {
    for (int column = 0; column < camera.width; ++column) {
      const auto i = std::size_t(row * camera.width + column);
      if (sphere.points[i].allFinite() && !used[i]) {
        ++unused_finite;
        EXPECT_TRUE(nearNan(sphere, row, column, 2)) << "pixel " << row << ", " << column;
      }
    }
  }
  EXPECT_LE(unused_finite, 10u);
}

TEST(OrganizedMesh, FullyFiniteGridGivesTwoFacesPerCell) {
  const analytic::Pinhole camera{17, 11, 40.0};
  // A sphere that fills the narrow field of view, and a tilted plane.
  const analytic::OrganizedCloud sphere =
      analytic::organizedSphere(camera, Eigen::Vector3d(0.0, 0.0, 2.0), 1.5);
  const analytic::OrganizedCloud plane =
      analytic::organizedPlane(camera, Eigen::Vector3d(0.2, -0.1, 1.0), 1.0);
  for (const auto* cloud : {&sphere, &plane}) {
    const Triangles faces = triangulate(*cloud);
    EXPECT_EQ(faces.size(), 2u * 16u * 10u);
    expectFacesFiniteAndFacingTheSensor(cloud->points, faces);
    const MeshTopology topology = topologyOf(cloud->points, faces);
    EXPECT_EQ(topology.non_manifold_edges, 0u);
    EXPECT_EQ(topology.misoriented_edges, 0u);
    EXPECT_EQ(topology.unused_vertices, 0u);
    EXPECT_EQ(topology.boundary_edges, 2u * (16u + 10u));
  }
}

// Rows stored bottom-up (or columns right-to-left) flip the image winding; faces still face
// the sensor.
TEST(OrganizedMesh, MirroredPixelOrderStillFacesTheSensor) {
  const analytic::Pinhole camera{20, 15, 40.0};
  analytic::OrganizedCloud plane = analytic::organizedPlane(camera, Eigen::Vector3d::UnitZ(), 1.0);
  Points mirrored;
  for (int row = camera.height - 1; row >= 0; --row) {
    for (int column = 0; column < camera.width; ++column) {
      mirrored.push_back(plane.points[std::size_t(row * camera.width + column)]);
    }
  }
  const Triangles faces =
      triangulateOrganizedGrid(mirrored, camera.width, camera.height, OrganizedMeshConfig());
  EXPECT_EQ(faces.size(), 2u * 19u * 14u);
  expectFacesFiniteAndFacingTheSensor(mirrored, faces);
}

TEST(OrganizedMesh, ShorterDiagonalIsChosen) {
  // One cell; p11 pulled towards p00 so the p00–p11 diagonal is the short one.
  const Points cell = {{0.0, 0.0, 1.0}, {1.0, 0.0, 1.0}, {0.0, 1.0, 1.0}, {0.6, 0.6, 1.0}};
  const Triangles faces = triangulateOrganizedGrid(cell, 2, 2, OrganizedMeshConfig());
  ASSERT_EQ(faces.size(), 2u);
  for (const auto& face : faces) {
    EXPECT_TRUE((face.array() == 0).any() && (face.array() == 3).any()) << face.transpose();
  }
  const Points other = {{0.0, 0.0, 1.0}, {1.0, 0.0, 1.0}, {0.0, 1.0, 1.0}, {1.4, 1.4, 1.0}};
  for (const auto& face : triangulateOrganizedGrid(other, 2, 2, OrganizedMeshConfig())) {
    EXPECT_TRUE((face.array() == 1).any() && (face.array() == 2).any()) << face.transpose();
  }
}

// Two fronto-parallel planes, z = 1 on the left half and z = 2 on the right: the cells across
// the jump have a 1 m edge against a ≈ 1–2 cm grid step, so no face may join the halves.
TEST(OrganizedMesh, DepthJumpProducesNoFaceAcrossIt) {
  const analytic::Pinhole camera{30, 20, 100.0};
  const analytic::OrganizedCloud step =
      analytic::renderOrganized(camera, [](const Eigen::Vector3d& ray) {
        analytic::Hit hit;
        hit.t = ray.x() < 0.0 ? 1.0 : 2.0;
        hit.normal = -Eigen::Vector3d::UnitZ();
        return hit;
      });
  const Triangles faces = triangulate(step);
  for (const auto& face : faces) {
    const double z0 = step.points[std::size_t(face[0])].z();
    EXPECT_EQ(step.points[std::size_t(face[1])].z(), z0) << face.transpose();
    EXPECT_EQ(step.points[std::size_t(face[2])].z(), z0) << face.transpose();
  }
  // Every cell except the one column of cells straddling the jump.
  EXPECT_EQ(faces.size(), 2u * (29u - 1u) * 19u);
  expectFacesFiniteAndFacingTheSensor(step.points, faces);
}

TEST(OrganizedMesh, NanHolesAreUsedByNoFace) {
  const analytic::Pinhole camera{25, 18, 50.0};
  analytic::OrganizedCloud plane =
      analytic::organizedPlane(camera, Eigen::Vector3d(0.0, 0.3, 1.0), 1.0);
  // One interior hole: its four cells keep one triangle each.
  const int hole = 7 * 25 + 9;
  plane.points[std::size_t(hole)] = Eigen::Vector3d::Constant(kNan);
  Triangles faces = triangulate(plane);
  EXPECT_EQ(faces.size(), 2u * 24u * 17u - 4u);
  // A random scatter of holes, seeded.
  const unsigned seed = 99;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pixel(0, 25 * 18 - 1);
  std::set<int> holes = {hole};
  for (int i = 0; i < 60; ++i) {
    holes.insert(pixel(rng));
  }
  for (const int h : holes) {
    plane.points[std::size_t(h)] = Eigen::Vector3d::Constant(kNan);
  }
  faces = triangulate(plane);
  ASSERT_FALSE(faces.empty()) << "seed " << seed;
  for (const auto& face : faces) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(holes.count(face[c]), 0u) << "seed " << seed << " face " << face.transpose();
    }
  }
  expectFacesFiniteAndFacingTheSensor(plane.points, faces);
  EXPECT_EQ(topologyOf(plane.points, faces).misoriented_edges, 0u) << "seed " << seed;
}

TEST(OrganizedMesh, DegenerateGridsAndSizeMismatchGiveNoFaces) {
  const analytic::Pinhole camera{10, 8, 20.0};
  const analytic::OrganizedCloud plane =
      analytic::organizedPlane(camera, Eigen::Vector3d::UnitZ(), 1.0);
  const OrganizedMeshConfig config;
  EXPECT_TRUE(triangulateOrganizedGrid(plane.points, 80, 1, config).empty());
  EXPECT_TRUE(triangulateOrganizedGrid(plane.points, 1, 80, config).empty());
  EXPECT_TRUE(triangulateOrganizedGrid(plane.points, 10, 9, config).empty());
  EXPECT_TRUE(triangulateOrganizedGrid(plane.points, 11, 8, config).empty());
  EXPECT_TRUE(triangulateOrganizedGrid(plane.points, -10, -8, config).empty());
  EXPECT_TRUE(triangulateOrganizedGrid(plane.points, 0, 0, config).empty());
  EXPECT_TRUE(triangulateOrganizedGrid(Points(), 0, 0, config).empty());
  EXPECT_TRUE(triangulateOrganizedGrid(plane.points, 65536, 65536, config).empty());
  const Points all_nan(80, Eigen::Vector3d::Constant(kNan));
  EXPECT_TRUE(triangulateOrganizedGrid(all_nan, 10, 8, config).empty());
  EXPECT_EQ(triangulateOrganizedGrid(plane.points, 10, 8, config).size(), 2u * 9u * 7u);
}

TEST(OrganizedMesh, NanEdgeRatioDropsEverythingAndInfiniteKeepsEverything) {
  const analytic::Pinhole camera{10, 8, 20.0};
  const analytic::OrganizedCloud plane =
      analytic::organizedPlane(camera, Eigen::Vector3d::UnitZ(), 1.0);
  OrganizedMeshConfig config;
  config.max_edge_ratio = kNan;
  EXPECT_TRUE(triangulateOrganizedGrid(plane.points, 10, 8, config).empty());
  config.max_edge_ratio = std::numeric_limits<double>::infinity();
  EXPECT_EQ(triangulateOrganizedGrid(plane.points, 10, 8, config).size(), 2u * 9u * 7u);
}

}  // namespace
}  // namespace freeform_inspection
