// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// The CAD's chord error (chord_error.h) against the analytic sagitta of tessellated cylinders,
// spheres and a torus, zero on flat faces, drafts and a flat face between coarse fillets, and
// against the shipped blade's coarse mesh measured from its fine one.
#include "freeform_inspection/chord_error.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "analytic_shapes.h"
#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh.h"
#include "freeform_inspection/mesh_query.h"

#ifndef FREEFORM_DATA_DIR
#error "FREEFORM_DATA_DIR must be defined as the absolute path of the package's data directory"
#endif

namespace freeform_inspection {
namespace {

using test::cylinderTube;
using test::icosphere;
using test::kShapePi;
using test::makeBox;
using test::torus;
using test::uvSphere;

// A closed prism: the convex outline (counter-clockwise in x-y) extruded along z by `height`,
// caps fanned from their centroid.
TriangleMesh prism(const std::vector<Eigen::Vector2d>& outline, double height) {
  TriangleMesh mesh;
  const auto n = static_cast<int>(outline.size());
  for (const double z : {0.0, height}) {
    for (const Eigen::Vector2d& p : outline) {
      mesh.vertices.emplace_back(p.x(), p.y(), z);
    }
  }
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : outline) {
    centre += p / static_cast<double>(n);
  }
  mesh.vertices.emplace_back(centre.x(), centre.y(), 0.0);
  mesh.vertices.emplace_back(centre.x(), centre.y(), height);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    mesh.faces.emplace_back(i, j, n + j);
    mesh.faces.emplace_back(i, n + j, n + i);
    mesh.faces.emplace_back(2 * n, j, i);
    mesh.faces.emplace_back(2 * n + 1, n + i, n + j);
  }
  mesh.face_normals = computeFaceNormals(mesh.vertices, mesh.faces);
  return mesh;
}

// Largest distance from the faces of a mesh whose vertices lie on a sphere of `radius` about
// the origin to that sphere: at the face point nearest the centre (the foot of the plane's
// perpendicular, which lies inside each face of these meshes).
double sphereChordError(const TriangleMesh& mesh, double radius) {
  const Points normals = computeFaceNormals(mesh.vertices, mesh.faces);
  double largest = 0.0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const double depth = std::abs(normals[f].dot(mesh.vertices[mesh.faces[f][0]]));
    largest = std::max(largest, radius - depth);
  }
  return largest;
}

TEST(ChordError, CylinderFacetsHaveTheSagittaOfTheirArc) {
  const double radius = 0.02;
  for (const int segments : {12, 24, 60}) {
    const ChordError error = estimateChordError(cylinderTube(radius, 0.05, segments, 4));
    const double sagitta = radius * (1.0 - std::cos(kShapePi / segments));
    for (const double face : error.face) {
      EXPECT_NEAR(face, sagitta, 0.02 * sagitta) << segments << " segments";
    }
    EXPECT_NEAR(error.max, sagitta, 0.02 * sagitta);
    EXPECT_NEAR(error.curved_area_share, 1.0, 1e-12);
  }
}

TEST(ChordError, SpheresAndTorusWithinAFifthOfTheirLargestChordError) {
  const double radius = 0.03;
  for (const int subdivisions : {1, 2, 3}) {
    const TriangleMesh mesh = icosphere(radius, subdivisions);
    const double truth = sphereChordError(mesh, radius);
    EXPECT_NEAR(estimateChordError(mesh).max, truth, 0.2 * truth) << subdivisions;
  }
  const TriangleMesh uv = uvSphere(radius, 12, 24);
  const double uv_truth = sphereChordError(uv, radius);
  EXPECT_NEAR(estimateChordError(uv).max, uv_truth, 0.2 * uv_truth);
  // The torus: its outer equator's facets, a quad of 2πR/u by 2πr/v on both circles' sagittas.
  const double major = 0.05;
  const double minor = 0.015;
  const int u = 48;
  const int v = 16;
  const double outer =
      (major + minor) * (1.0 - std::cos(kShapePi / u)) + minor * (1.0 - std::cos(kShapePi / v));
  EXPECT_NEAR(estimateChordError(torus(major, minor, u, v)).max, outer, 0.2 * outer);
}

TEST(ChordError, FlatFacesDraftsAndAFaceBetweenFilletsStayZero) {
  const ChordError box = estimateChordError(makeBox(Eigen::Vector3d(0.02, 0.01, 0.005)));
  EXPECT_EQ(box.max, 0.0);
  EXPECT_EQ(box.curved_area_share, 0.0);
  // A block whose long sides lean in by a 3° draft, and a shallow roof of two faces meeting at
  // 3°: each face turns on one side only, as drawn edges do.
  const double lean = 0.04 * std::tan(3.0 * kShapePi / 180.0);
  const std::vector<Eigen::Vector2d> draft = {
      {0.0, 0.0}, {0.05, 0.0}, {0.05 - lean, 0.04}, {lean, 0.04}};
  EXPECT_EQ(estimateChordError(prism(draft, 0.03)).max, 0.0);
  const std::vector<Eigen::Vector2d> roof = {{0.0, 0.0},
                                             {0.06, 0.0},
                                             {0.06, 0.01},
                                             {0.03, 0.01 + 0.03 * std::tan(3.0 * kShapePi / 180.0)},
                                             {0.0, 0.01}};
  EXPECT_EQ(estimateChordError(prism(roof, 0.03)).max, 0.0);
  // A 40 x 20 mm slab with 3 mm corner fillets of 4 facets: the flat sides (37 and 17 mm
  // between fillet facets of 1.2 mm) carry nothing; the fillets' facets their sagitta.
  const double r = 0.003;
  const int k = 4;
  std::vector<Eigen::Vector2d> outline;
  const Eigen::Vector2d centres[] = {
      {0.02 - r, -0.01 + r}, {0.02 - r, 0.01 - r}, {-0.02 + r, 0.01 - r}, {-0.02 + r, -0.01 + r}};
  for (int corner = 0; corner < 4; ++corner) {
    for (int i = 0; i <= k; ++i) {
      const double phi = (corner - 1 + static_cast<double>(i) / k) * 0.5 * kShapePi;
      outline.push_back(centres[corner] + r * Eigen::Vector2d(std::cos(phi), std::sin(phi)));
    }
  }
  const TriangleMesh slab = prism(outline, 0.01);
  const ChordError fillets = estimateChordError(slab);
  const double sagitta = r * (1.0 - std::cos(0.25 * kShapePi / k));
  EXPECT_NEAR(fillets.max, sagitta, 0.2 * sagitta);
  for (std::size_t f = 0; f < slab.faces.size(); ++f) {  // prism(): four faces per side
    const std::size_t i = f / 4;
    const double side = (outline[(i + 1) % outline.size()] - outline[i]).norm();
    if (std::abs(slab.face_normals[f].z()) > 0.5 || side > 0.01) {  // caps and flat sides
      EXPECT_LE(fillets.face[f], 0.05 * sagitta) << "face " << f;
    }
  }
}

// data/blade/blade.stl is the blade of blade_fine.stl sampled half as densely along its sections
// and a quarter along its span. Its worst facets are the superellipse platform's ends: there
// the chords of 41 and 81 stations (uniform in x) miss the exact outline |x/35|^4 + |y/15|^4 = 1
// (mm) by 0.83 and 0.42 mm. The fine mesh's vertices lie on the exact surface, so the distance
// from them to the coarse mesh measures its chord error from below (0.60 mm).
TEST(ChordError, ShippedBladePlatformEndsAgainstTheirExactOutline) {
  const std::string dir = std::string(FREEFORM_DATA_DIR) + "/blade/";
  const MeshLoadResult coarse = loadMesh(dir + "blade.stl", 0.001);
  const MeshLoadResult fine = loadMesh(dir + "blade_fine.stl", 0.001);
  ASSERT_TRUE(coarse.status.ok() && fine.status.ok());
  const MeshQuery query(coarse.mesh);
  double measured = 0.0;
  for (const Eigen::Vector3d& v : fine.mesh.vertices) {
    measured = std::max(measured, query.closest(v, 0.01).distance);
  }
  EXPECT_NEAR(measured, 6.0e-4, 0.2e-4);
  const ChordError error = estimateChordError(coarse.mesh);
  EXPECT_GT(error.max, measured);                // 0.62 mm
  EXPECT_LT(error.max, 8.3e-4);                  // the exact outline's
  EXPECT_GT(std::abs(error.max_at.x()), 0.028);  // at a platform end
  EXPECT_LT(error.max_at.z(), 0.015);
  // Twice the stations: half the chord error.
  const double ratio = estimateChordError(fine.mesh).max / error.max;
  EXPECT_GT(ratio, 0.4);
  EXPECT_LT(ratio, 0.6);
}

}  // namespace
}  // namespace freeform_inspection
