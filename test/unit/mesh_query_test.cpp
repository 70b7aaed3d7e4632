// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/mesh_query.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "analytic_shapes.h"
#include "test_shapes.h"
#include <gtest/gtest.h>

namespace freeform_inspection {
namespace {

constexpr unsigned kSeed = 20260311;
constexpr double kInf = std::numeric_limits<double>::infinity();

Points randomPoints(int count, double half_width, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(-half_width, half_width);
  Points points;
  for (int i = 0; i < count; ++i) {
    const double x = coordinate(rng);
    const double y = coordinate(rng);
    points.emplace_back(x, y, coordinate(rng));
  }
  return points;
}

// A(0,0,0), B(1,0,0), C(0,1,0): normal +z.
TriangleMesh unitTriangle() {
  TriangleMesh mesh;
  mesh.vertices = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
  mesh.faces = {{0, 1, 2}};
  return mesh;
}

// Regular tetrahedron around the origin, faces turned outward. Its dihedral angles are acute
// (face normals at cos = −1/3), so a face normal can point away from a query that is outside.
TriangleMesh tetrahedron() {
  TriangleMesh mesh;
  mesh.vertices = {{1.0, 1.0, 1.0}, {1.0, -1.0, -1.0}, {-1.0, 1.0, -1.0}, {-1.0, -1.0, 1.0}};
  mesh.faces = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (auto& f : mesh.faces) {
    const Eigen::Vector3d a = mesh.vertices[static_cast<std::size_t>(f[0])];
    const Eigen::Vector3d n = (mesh.vertices[static_cast<std::size_t>(f[1])] - a)
                                  .cross(mesh.vertices[static_cast<std::size_t>(f[2])] - a);
    if (n.dot(a) < 0.0) {
      std::swap(f[1], f[2]);
    }
  }
  return mesh;
}

Eigen::Vector3d faceNormal(const TriangleMesh& mesh, int face) {
  const auto& f = mesh.faces[static_cast<std::size_t>(face)];
  const Eigen::Vector3d a = mesh.vertices[static_cast<std::size_t>(f[0])];
  return (mesh.vertices[static_cast<std::size_t>(f[1])] - a)
      .cross(mesh.vertices[static_cast<std::size_t>(f[2])] - a)
      .normalized();
}

// Exact signed distance to the axis-aligned box with corners ±h.
double boxSignedDistance(const Eigen::Vector3d& q, const Eigen::Vector3d& h) {
  const Eigen::Vector3d d = q.cwiseAbs() - h;
  return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
}

// Smallest distance from the origin to a face plane: an inscribed icosphere lies between this
// radius and R (the largest chord sagitta is R − this).
double inRadius(const TriangleMesh& mesh) {
  double smallest = kInf;
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) {
    const Eigen::Vector3d& a =
        mesh.vertices[static_cast<std::size_t>(mesh.faces[static_cast<std::size_t>(f)][0])];
    smallest = std::min(smallest, std::abs(faceNormal(mesh, f).dot(a)));
  }
  return smallest;
}

// Reference distance, written differently from the library's region walk: the foot point on
// the plane if it is inside the triangle, else the nearest of the three edges.
double segmentDistance(const Eigen::Vector3d& p,
                       const Eigen::Vector3d& a,
                       const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

double triangleDistance(const Eigen::Vector3d& p,
                        const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
  const Eigen::Vector3d foot = p - n.dot(p - a) * n;
  const bool inside = (b - a).cross(foot - a).dot(n) >= 0.0 &&
                      (c - b).cross(foot - b).dot(n) >= 0.0 &&
                      (a - c).cross(foot - c).dot(n) >= 0.0;
  if (inside) {
    return std::abs(n.dot(p - a));
  }
  return std::min({segmentDistance(p, a, b), segmentDistance(p, b, c), segmentDistance(p, c, a)});
}

// Generalized winding number (Van Oosterom–Strackee solid angles): 1 inside a closed outward
// mesh, 0 outside.
double windingNumber(const TriangleMesh& mesh, const Eigen::Vector3d& q) {
  double total = 0.0;
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d a = mesh.vertices[static_cast<std::size_t>(f[0])] - q;
    const Eigen::Vector3d b = mesh.vertices[static_cast<std::size_t>(f[1])] - q;
    const Eigen::Vector3d c = mesh.vertices[static_cast<std::size_t>(f[2])] - q;
    const double la = a.norm();
    const double lb = b.norm();
    const double lc = c.norm();
    total += 2.0 * std::atan2(a.dot(b.cross(c)),
                              la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return total / (4.0 * test::kShapePi);
}

struct Expected {
  const char* region;
  Eigen::Vector3d query;
  Eigen::Vector3d point;
  double signed_distance;
};

TEST(MeshQuery, ClosestPointInEachVoronoiRegionOfATriangle) {
  const MeshQuery query(unitTriangle());
  ASSERT_TRUE(query.status().ok()) << query.status().message;
  // Worked by hand: project onto the plane, clamp to the region's feature. On a single
  // triangle every pseudo-normal is the face normal +z, so the sign is the sign of z.
  const std::vector<Expected> cases = {
      {"face above", {0.25, 0.25, 0.5}, {0.25, 0.25, 0.0}, 0.5},
      {"face below", {0.2, 0.3, -2.0}, {0.2, 0.3, 0.0}, -2.0},
      {"vertex A", {-1.0, -1.0, 1.0}, {0.0, 0.0, 0.0}, std::sqrt(3.0)},
      {"vertex B", {2.0, -0.5, -1.0}, {1.0, 0.0, 0.0}, -1.5},
      {"vertex C", {-0.5, 3.0, 0.5}, {0.0, 1.0, 0.0}, std::sqrt(4.5)},
      {"edge AB", {0.3, -2.0, 1.0}, {0.3, 0.0, 0.0}, std::sqrt(5.0)},
      {"edge BC", {0.9, 0.5, 0.3}, {0.7, 0.3, 0.0}, std::sqrt(0.17)},
      {"edge CA", {-1.0, 0.6, -0.5}, {0.0, 0.6, 0.0}, -std::sqrt(1.25)},
  };
  for (const auto& c : cases) {
    const ClosestPoint found = query.closest(c.query);
    ASSERT_TRUE(found.found) << c.region;
    EXPECT_EQ(found.face, 0) << c.region;
    EXPECT_NEAR((found.point - c.point).norm(), 0.0, 1e-15) << c.region;
    EXPECT_NEAR(found.distance, std::abs(c.signed_distance), 1e-15) << c.region;
    EXPECT_NEAR(found.signed_distance, c.signed_distance, 1e-15) << c.region;
    EXPECT_NEAR((found.normal - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15) << c.region;
  }
  // On the surface: distance exactly 0, and so is the signed distance.
  const ClosestPoint on = query.closest({0.25, 0.5, 0.0});
  ASSERT_TRUE(on.found);
  EXPECT_EQ(on.distance, 0.0);
  EXPECT_EQ(on.signed_distance, 0.0);
}

TEST(MeshQuery, IcosphereDistanceMatchesTheSphereWithinTheSagitta) {
  const double radius = 1.0;
  const TriangleMesh mesh = test::icosphere(radius, 3);  // 1280 faces
  const MeshQuery query(mesh);
  ASSERT_TRUE(query.status().ok()) << query.status().message;
  const double sagitta = radius - inRadius(mesh);
  ASSERT_GT(sagitta, 0.0);
  ASSERT_LT(sagitta, 0.01);
  std::cout << "icosphere: seed " << kSeed << ", largest sagitta " << sagitta << " m\n";
  int inside = 0;
  int outside = 0;
  for (const auto& q : randomPoints(2000, 2.0, kSeed)) {
    const ClosestPoint found = query.closest(q);
    ASSERT_TRUE(found.found);
    const double exact = q.norm() - radius;
    // The mesh lies between the radii R − sagitta and R, hence this bound.
    EXPECT_NEAR(found.signed_distance, exact, sagitta + 1e-12) << "seed " << kSeed;
    EXPECT_NEAR(found.distance, std::abs(found.signed_distance), 0.0);
    EXPECT_NEAR(found.point.norm(), radius, sagitta + 1e-12);
    // Outside the shell the sign is certain.
    if (q.norm() > radius) {
      EXPECT_GT(found.signed_distance, 0.0) << "seed " << kSeed;
      ++outside;
    } else if (q.norm() < radius - sagitta) {
      EXPECT_LT(found.signed_distance, 0.0) << "seed " << kSeed;
      ++inside;
    }
  }
  EXPECT_GT(inside, 100);
  EXPECT_GT(outside, 100);
}

TEST(MeshQuery, BoxSignedDistanceIsExactNearEdgesAndCorners) {
  const Eigen::Vector3d h(1.0, 0.5, 0.25);
  const MeshQuery query(test::makeBox(h));
  ASSERT_TRUE(query.status().ok()) << query.status().message;
  // Queries clustered around the 8 corners and 12 edge midpoints, inside and outside.
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  Points anchors;
  for (int i = 0; i < 8; ++i) {
    anchors.emplace_back(
        (i & 1 ? 1 : -1) * h.x(), (i & 2 ? 1 : -1) * h.y(), (i & 4 ? 1 : -1) * h.z());
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Vector3d mid = anchors.back();
      mid[axis] = 0.0;
      anchors.push_back(mid);
    }
  }
  int outside_near_feature = 0;
  for (const auto& anchor : anchors) {
    for (int k = 0; k < 100; ++k) {
      const Eigen::Vector3d q = anchor + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
      const double exact = boxSignedDistance(q, h);
      const ClosestPoint found = query.closest(q);
      ASSERT_TRUE(found.found);
      EXPECT_NEAR(found.signed_distance, exact, 1e-12)
          << "seed " << kSeed << " q " << q.transpose();
      if (exact > 0.0 && (q.cwiseAbs() - h).maxCoeff() > 0.0 &&
          ((q.cwiseAbs() - h).array() > 0.0).count() >= 2) {
        ++outside_near_feature;  // closest point on an edge or at a corner
      }
    }
  }
  EXPECT_GT(outside_near_feature, 200);
  // Beside an edge, level with one face: q − p is perpendicular to that face's normal, so the
  // naive face-normal sign is 0 for one of the two equally close faces.
  const ClosestPoint beside = query.closest({1.5, 0.5, 0.0});
  ASSERT_TRUE(beside.found);
  EXPECT_DOUBLE_EQ(beside.signed_distance, 0.5);
}

TEST(MeshQuery, PseudoNormalSignIsRightWhereTheFaceNormalIsWrong) {
  const TriangleMesh mesh = tetrahedron();
  const MeshQuery query(mesh);
  ASSERT_TRUE(query.status().ok()) << query.status().message;
  // Edge v0–v1 is shared by faces 0 and 1. Go out mostly along face 1's normal: the closest
  // point is on the edge, both faces are equally close, and face 0's normal says "inside".
  const Eigen::Vector3d n0 = faceNormal(mesh, 0);
  const Eigen::Vector3d n1 = faceNormal(mesh, 1);
  const Eigen::Vector3d mid = 0.5 * (mesh.vertices[0] + mesh.vertices[1]);
  const Eigen::Vector3d q_edge = mid + 0.1 * (0.05 * n0 + n1);
  EXPECT_LT((q_edge - mid).dot(n0), 0.0);  // the naive sign through face 0 would be negative
  const ClosestPoint edge = query.closest(q_edge);
  ASSERT_TRUE(edge.found);
  EXPECT_NEAR((edge.point - mid).norm(), 0.0, 1e-12);
  EXPECT_NEAR(edge.signed_distance, (q_edge - mid).norm(), 1e-12);
  // The same at vertex v0 (faces 0, 1, 2): mostly along face 2's normal.
  const Eigen::Vector3d n2 = faceNormal(mesh, 2);
  const Eigen::Vector3d& v0 = mesh.vertices[0];
  const Eigen::Vector3d q_vertex = v0 + 0.1 * (0.05 * n0 + 0.05 * n1 + n2);
  EXPECT_LT((q_vertex - v0).dot(n0), 0.0);
  EXPECT_LT((q_vertex - v0).dot(n1), 0.0);
  const ClosestPoint vertex = query.closest(q_vertex);
  ASSERT_TRUE(vertex.found);
  EXPECT_NEAR((vertex.point - v0).norm(), 0.0, 1e-12);
  EXPECT_NEAR(vertex.signed_distance, (q_vertex - v0).norm(), 1e-12);
  // And just inside the same vertex: negative.
  const ClosestPoint in = query.closest(0.99 * v0);
  ASSERT_TRUE(in.found);
  EXPECT_LT(in.signed_distance, 0.0);
}

TEST(MeshQuery, MaxDistanceIsRespected) {
  const MeshQuery query(test::makeBox(Eigen::Vector3d(1.0, 1.0, 1.0)));
  ASSERT_TRUE(query.status().ok());
  const Eigen::Vector3d q(1.5, 0.1, 0.2);  // 0.5 m from the x = 1 face
  EXPECT_FALSE(query.closest(q, 0.4).found);
  EXPECT_FALSE(query.closest(q, 0.4999999).found);
  const ClosestPoint exactly = query.closest(q, 0.5);
  ASSERT_TRUE(exactly.found);  // the bound is inclusive
  EXPECT_DOUBLE_EQ(exactly.distance, 0.5);
  EXPECT_TRUE(query.closest(q, 0.6).found);
  EXPECT_FALSE(query.closest(q, -1.0).found);
  EXPECT_FALSE(query.closest(q, std::nan("")).found);
  // Inside, 0.3 m from the nearest face.
  EXPECT_FALSE(query.closest({0.7, 0.0, 0.0}, 0.25).found);
  EXPECT_NEAR(query.closest({0.7, 0.0, 0.0}, 0.35).signed_distance, -0.3, 1e-15);
  // The batch version applies the same bound.
  const auto batch = query.closest(Points{q, {0.0, 0.0, 1.2}}, 0.3);
  ASSERT_EQ(batch.size(), 2u);
  EXPECT_FALSE(batch[0].found);
  EXPECT_TRUE(batch[1].found);
}

TEST(MeshQuery, ClosestFacingSkipsTheFacesTurnedOtherwise) {
  // A wall 1 mm thick (z in [-0.5, 0.5] mm) and 20 mm wide: a point 0.2 mm above its mid-plane
  // is nearest the top face, but a surface facing down lies 0.7 mm away, on the bottom.
  const MeshQuery wall(test::makeBox(Eigen::Vector3d(0.01, 0.01, 0.0005)));
  ASSERT_TRUE(wall.status().ok());
  const Eigen::Vector3d q(0.001, -0.002, 0.0002);
  const double cos40 = std::cos(40.0 * 3.14159265358979323846 / 180.0);
  const ClosestPoint nearest = wall.closest(q, 0.01);
  ASSERT_TRUE(nearest.found);
  EXPECT_NEAR(nearest.distance, 0.0003, 1e-12);
  EXPECT_NEAR(nearest.normal.z(), 1.0, 1e-12);
  const ClosestPoint down = wall.closestFacing(q, {0.0, 0.0, -1.0}, cos40, true, 0.01);
  ASSERT_TRUE(down.found);
  EXPECT_NEAR(down.distance, 0.0007, 1e-12);
  EXPECT_NEAR(down.normal.z(), -1.0, 1e-12);
  EXPECT_NEAR(down.signed_distance, -0.0007, 1e-12);  // inside the material, seen from below
  // Within 30° of down, not only down itself; compared as lines, the top face faces both ways.
  const Eigen::Vector3d tilted(std::sin(0.5), 0.0, -std::cos(0.5));
  EXPECT_NEAR(wall.closestFacing(q, tilted, cos40, true, 0.01).distance, 0.0007, 1e-12);
  EXPECT_NEAR(wall.closestFacing(q, {0.0, 0.0, -1.0}, cos40, false, 0.01).distance, 0.0003, 1e-12);
  // Facing +x: only the wall's end 9 mm away; the bound and an unnormalised normal as closest().
  EXPECT_NEAR(wall.closestFacing(q, {2.0, 0.0, 0.0}, cos40, true, 0.01).distance, 0.009, 1e-12);
  EXPECT_FALSE(wall.closestFacing(q, {1.0, 0.0, 0.0}, cos40, true, 0.005).found);
  EXPECT_FALSE(wall.closestFacing(q, {0.0, 0.0, -1.0}, cos40, true, 0.0006).found);
  // No normal to go by: every face counts.
  EXPECT_NEAR(
      wall.closestFacing(q, Eigen::Vector3d::Zero(), cos40, true, 0.01).distance, 0.0003, 1e-12);
}

TEST(MeshQuery, BatchEqualsSingleQueries) {
  const MeshQuery query(test::torus(1.0, 0.3, 32, 16));
  ASSERT_TRUE(query.status().ok());
  const Points queries = randomPoints(3000, 1.6, kSeed);
  for (const double max_distance : {kInf, 0.2}) {
    const std::vector<ClosestPoint> batch = query.closest(queries, max_distance);
    ASSERT_EQ(batch.size(), queries.size());
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const ClosestPoint single = query.closest(queries[i], max_distance);
      ASSERT_EQ(batch[i].found, single.found) << i;
      EXPECT_EQ(batch[i].face, single.face) << i;
      EXPECT_EQ(batch[i].point, single.point) << i;
      EXPECT_EQ(batch[i].normal, single.normal) << i;
      EXPECT_EQ(batch[i].distance, single.distance) << i;
      EXPECT_EQ(batch[i].signed_distance, single.signed_distance) << i;
    }
  }
  EXPECT_TRUE(query.closest(Points{}).empty());
}

// The batch closestFacing() is the single query per point, whatever hint its search starts
// from (a hint facing the wrong way included).
TEST(MeshQuery, BatchClosestFacingEqualsSingleQueriesWhateverTheHints) {
  const MeshQuery query(test::torus(1.0, 0.3, 32, 16));
  ASSERT_TRUE(query.status().ok());
  const Points queries = randomPoints(2000, 1.6, kSeed);
  std::mt19937 rng(kSeed + 2);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Points normals;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    // A tenth of the points without a normal: every face counts for them.
    normals.push_back(i % 10 == 0 ? Eigen::Vector3d::Zero()
                                  : Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)));
  }
  const auto faces = static_cast<int>(query.mesh().faces.size());
  std::uniform_int_distribution<int> face(-1, faces - 1);
  std::vector<int> random_hints;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    random_hints.push_back(face(rng));
  }
  const double cos60 = 0.5;
  for (const bool oriented : {true, false}) {
    for (const std::vector<int>& hints : {random_hints, std::vector<int>{}}) {
      const std::vector<ClosestPoint> batch =
          query.closestFacing(queries, normals, cos60, oriented, 0.4, hints);
      ASSERT_EQ(batch.size(), queries.size());
      std::size_t found = 0;
      for (std::size_t i = 0; i < queries.size(); ++i) {
        const ClosestPoint single =
            query.closestFacing(queries[i], normals[i], cos60, oriented, 0.4);
        ASSERT_EQ(batch[i].found, single.found) << i;
        EXPECT_EQ(batch[i].face, single.face) << i;
        EXPECT_EQ(batch[i].point, single.point) << i;
        EXPECT_EQ(batch[i].distance, single.distance) << i;
        found += single.found ? 1 : 0;
      }
      EXPECT_GT(found, queries.size() / 10);  // the comparison is not between empty answers
    }
  }
}

// A hint only bounds the search: any face, near or far, right or wrong, invalid or none, gives
// the answer without hints to the last bit (ties included: a point on the torus's axis is at
// the same distance from a whole ring of faces).
TEST(MeshQuery, HintsChangeNoAnswer) {
  const MeshQuery query(test::torus(1.0, 0.3, 32, 16));
  ASSERT_TRUE(query.status().ok());
  Points queries = randomPoints(3000, 1.6, kSeed);
  queries.emplace_back(0.0, 0.0, 0.0);
  queries.emplace_back(0.0, 0.0, 0.5);
  const auto faces = static_cast<int>(query.mesh().faces.size());
  std::mt19937 rng(kSeed + 1);
  std::uniform_int_distribution<int> face(-1, faces);  // −1 and `faces` are no face
  for (const double max_distance : {kInf, 0.2}) {
    const std::vector<ClosestPoint> plain = query.closest(queries, max_distance);
    std::vector<int> random_hints;
    std::vector<int> right_hints;
    for (std::size_t i = 0; i < queries.size(); ++i) {
      random_hints.push_back(face(rng));
      right_hints.push_back(plain[i].face);
    }
    for (const std::vector<int>& hints : {random_hints, right_hints, std::vector<int>{}}) {
      const std::vector<ClosestPoint> hinted = query.closest(queries, max_distance, hints);
      ASSERT_EQ(hinted.size(), queries.size());
      for (std::size_t i = 0; i < queries.size(); ++i) {
        ASSERT_EQ(hinted[i].found, plain[i].found) << i;
        EXPECT_EQ(hinted[i].face, plain[i].face) << i;
        EXPECT_EQ(hinted[i].point, plain[i].point) << i;
        EXPECT_EQ(hinted[i].distance, plain[i].distance) << i;
        EXPECT_EQ(hinted[i].signed_distance, plain[i].signed_distance) << i;
      }
    }
  }
}

TEST(MeshQuery, ClosestMatchesBruteForceAndWindingNumber) {
  // 576 faces, irregular (noisy) and not convex.
  const TriangleMesh mesh = test::addNormalNoise(test::torus(1.0, 0.35, 24, 12), 0.02, kSeed);
  const MeshQuery query(mesh);
  ASSERT_TRUE(query.status().ok());
  std::cout << "brute force: seed " << kSeed << ", " << mesh.faces.size() << " faces\n";
  int signs_checked = 0;
  for (const auto& q : randomPoints(1000, 1.6, kSeed + 1)) {
    double best = kInf;
    for (const auto& f : mesh.faces) {
      best = std::min(best,
                      triangleDistance(q,
                                       mesh.vertices[static_cast<std::size_t>(f[0])],
                                       mesh.vertices[static_cast<std::size_t>(f[1])],
                                       mesh.vertices[static_cast<std::size_t>(f[2])]));
    }
    const ClosestPoint found = query.closest(q);
    ASSERT_TRUE(found.found);
    EXPECT_NEAR(found.distance, best, 1e-12) << "seed " << kSeed << " q " << q.transpose();
    EXPECT_NEAR((q - found.point).norm(), found.distance, 1e-12);
    const double winding = windingNumber(mesh, q);
    ASSERT_LT(std::min(std::abs(winding), std::abs(winding - 1.0)), 1e-6);
    if (found.distance > 1e-9) {
      EXPECT_EQ(found.signed_distance<0.0, winding> 0.5)
          << "seed " << kSeed << " q " << q.transpose() << " d " << found.signed_distance;
      ++signs_checked;
    }
  }
  EXPECT_EQ(signs_checked, 1000);
}

TEST(MeshQuery, FacesSkippedByTheirPlaneNeverHoldTheAnswer) {
  // A face whose plane lies farther than the best so far is skipped unread. Stacks of parallel
  // sheets make most faces skippable; slivers (whose computed plane may point anywhere) and a
  // part 1 km from the origin (where the plane's offset cancels) are where the bound could lie.
  TriangleMesh mesh;
  std::mt19937 rng(kSeed + 7);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  const Eigen::Vector3d far(1000.0, -700.0, 300.0);
  for (int sheet = 0; sheet < 5; ++sheet) {
    for (int i = 0; i < 6; ++i) {
      for (int j = 0; j < 6; ++j) {
        const auto first = static_cast<int>(mesh.vertices.size());
        const double z = 0.1 * sheet;
        for (const auto& [u, v] : {std::pair{0, 0}, std::pair{1, 0}, std::pair{0, 1}}) {
          mesh.vertices.push_back(far + Eigen::Vector3d(0.1 * (i + u) + jitter(rng),
                                                        0.1 * (j + v) + jitter(rng),
                                                        z + jitter(rng)));
        }
        mesh.faces.push_back({first, first + 1, first + 2});
      }
    }
  }
  for (int k = 0; k < 20; ++k) {  // slivers: a long edge and a corner 1e-9 off it
    const auto first = static_cast<int>(mesh.vertices.size());
    const Eigen::Vector3d a = far + Eigen::Vector3d(jitter(rng), jitter(rng), 0.25 + jitter(rng));
    const Eigen::Vector3d b = a + Eigen::Vector3d(0.5, 0.3 + jitter(rng), 0.01);
    mesh.vertices.push_back(a);
    mesh.vertices.push_back(b);
    mesh.vertices.push_back(0.5 * (a + b) + Eigen::Vector3d(0.0, 0.0, 1e-9));
    mesh.faces.push_back({first, first + 1, first + 2});
  }
  const MeshQuery query(mesh);
  ASSERT_TRUE(query.status().ok()) << query.status().message;
  std::uniform_real_distribution<double> around(-0.1, 0.7);
  int unique_minima = 0;
  for (int n = 0; n < 2000; ++n) {
    const Eigen::Vector3d q = far + Eigen::Vector3d(around(rng), around(rng), around(rng) - 0.1);
    std::vector<double> distances;
    for (const auto& f : mesh.faces) {
      distances.push_back(triangleDistance(q,
                                           mesh.vertices[static_cast<std::size_t>(f[0])],
                                           mesh.vertices[static_cast<std::size_t>(f[1])],
                                           mesh.vertices[static_cast<std::size_t>(f[2])]));
    }
    const auto nearest = std::min_element(distances.begin(), distances.end());
    const auto face = static_cast<int>(nearest - distances.begin());
    for (const double max_distance : {kInf, 0.08}) {
      const ClosestPoint found = query.closest(q, max_distance);
      ASSERT_EQ(found.found, *nearest <= max_distance) << n;
      if (!found.found) {
        continue;
      }
      EXPECT_NEAR(found.distance, *nearest, 1e-12) << n << " " << q.transpose();
      std::vector<double> others = distances;
      others.erase(others.begin() + face);
      if (*std::min_element(others.begin(), others.end()) > *nearest + 1e-9) {
        EXPECT_EQ(found.face, face) << n;
        unique_minima += max_distance == kInf ? 1 : 0;
      }
    }
  }
  EXPECT_GT(unique_minima, 1500);
}

TEST(MeshQuery, DegenerateTrianglesGiveFiniteAnswers) {
  TriangleMesh mesh = unitTriangle();
  mesh.vertices.push_back({2.0, 0.0, 0.0});
  mesh.vertices.push_back({3.0, 0.0, 0.0});
  mesh.vertices.push_back({5.0, 5.0, 5.0});
  mesh.faces.push_back({1, 3, 4});  // collinear: zero area
  mesh.faces.push_back({5, 5, 5});  // one point
  mesh.faces.push_back({2, 5, 2});  // repeated index: a segment
  const MeshQuery query(mesh);
  ASSERT_TRUE(query.status().ok()) << query.status().message;
  for (const auto& q : randomPoints(500, 6.0, kSeed)) {
    const ClosestPoint found = query.closest(q);
    ASSERT_TRUE(found.found);
    EXPECT_TRUE(found.point.allFinite());
    EXPECT_TRUE(found.normal.allFinite());
    EXPECT_TRUE(std::isfinite(found.distance));
    EXPECT_TRUE(std::isfinite(found.signed_distance));
    EXPECT_NEAR((q - found.point).norm(), found.distance, 1e-12);
  }
  // On the collinear face's far end, and at the lone point.
  const ClosestPoint end = query.closest({3.5, 0.0, 0.0});
  ASSERT_TRUE(end.found);
  EXPECT_DOUBLE_EQ(end.distance, 0.5);
  const ClosestPoint lone = query.closest({5.0, 5.0, 6.0});
  ASSERT_TRUE(lone.found);
  EXPECT_NEAR(lone.distance, 1.0, 1e-15);
}

TEST(MeshQuery, RayOnABoxHasHandComputedT) {
  const MeshQuery query(test::makeBox(Eigen::Vector3d(1.0, 1.0, 1.0)));
  ASSERT_TRUE(query.status().ok());
  const Eigen::Vector3d origin(-5.0, 0.2, 0.3);
  const Eigen::Vector3d direction(2.0, 0.0, 0.0);  // not unit: t is still in metres
  const RayHit hit = query.castRay(origin, direction);
  ASSERT_TRUE(hit.hit);
  EXPECT_DOUBLE_EQ(hit.t, 4.0);
  EXPECT_NEAR((hit.point - Eigen::Vector3d(-1.0, 0.2, 0.3)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((hit.normal - Eigen::Vector3d(-1.0, 0.0, 0.0)).norm(), 0.0, 1e-15);
  // t_max is inclusive, t_min exclusive: the next hit is the far face at t = 6.
  EXPECT_TRUE(query.castRay(origin, direction, 0.0, 4.0).hit);
  EXPECT_FALSE(query.castRay(origin, direction, 0.0, 3.9).hit);
  const RayHit far = query.castRay(origin, direction, 4.0);
  ASSERT_TRUE(far.hit);
  EXPECT_DOUBLE_EQ(far.t, 6.0);
  EXPECT_NEAR((far.normal - Eigen::Vector3d(1.0, 0.0, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(query.castRay(origin, direction, 4.5, 10.0).t, 6.0);
  EXPECT_FALSE(query.castRay(origin, direction, 6.0).hit);
  // A negative t_min looks behind the origin.
  const RayHit behind = query.castRay({5.0, 0.2, 0.3}, {1.0, 0.0, 0.0}, -10.0);
  ASSERT_TRUE(behind.hit);
  EXPECT_DOUBLE_EQ(behind.t, -6.0);
  // Diagonal ray to a face: (1, 1, 1) direction from (−3, −2.5, −2.8) reaches x = −1 at
  // t = 2·√3, where y = −0.5 and z = −0.8.
  const RayHit diagonal = query.castRay({-3.0, -2.5, -2.8}, {1.0, 1.0, 1.0});
  ASSERT_TRUE(diagonal.hit);
  EXPECT_NEAR(diagonal.t, 2.0 * std::sqrt(3.0), 1e-14);
  EXPECT_NEAR((diagonal.point - Eigen::Vector3d(-1.0, -0.5, -0.8)).norm(), 0.0, 1e-14);
  // From inside, the far side: its outward normal points along the ray.
  const RayHit from_inside = query.castRay({0.1, 0.3, 0.0}, {0.0, 0.0, 1.0});
  ASSERT_TRUE(from_inside.hit);
  EXPECT_DOUBLE_EQ(from_inside.t, 1.0);
  EXPECT_NEAR((from_inside.normal - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15);
  // Misses.
  EXPECT_FALSE(query.castRay(origin, {-1.0, 0.0, 0.0}).hit);
  EXPECT_FALSE(query.castRay(origin, {0.0, 1.0, 0.0}).hit);
  EXPECT_FALSE(query.castRay({-5.0, 1.5, 0.0}, {1.0, 0.0, 0.0}).hit);
  EXPECT_FALSE(query.castRay(origin, Eigen::Vector3d::Zero()).hit);
  EXPECT_FALSE(query.castRay(origin, {std::nan(""), 0.0, 0.0}).hit);
  EXPECT_FALSE(query.castRay(origin, direction, 5.0, 5.0).hit);
}

TEST(MeshQuery, RayOnAnIcosphere) {
  const double radius = 1.0;
  const TriangleMesh mesh = test::icosphere(radius, 3);
  const MeshQuery query(mesh);
  ASSERT_TRUE(query.status().ok());
  const double sagitta = radius - inRadius(mesh);
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> gaussian;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d u =
        Eigen::Vector3d(gaussian(rng), gaussian(rng), gaussian(rng)).normalized();
    // From 5 m out towards the centre: the surface is between t = 5 − R and 5 − R + sagitta.
    const RayHit in = query.castRay(5.0 * u, -u);
    ASSERT_TRUE(in.hit);
    EXPECT_GE(in.t, 5.0 - radius - 1e-12);
    EXPECT_LE(in.t, 5.0 - radius + sagitta + 1e-12);
    EXPECT_GT(in.normal.dot(u), 0.9);  // the face the ray meets looks back at it
    EXPECT_NEAR((in.point - 5.0 * u + in.t * u).norm(), 0.0, 1e-12);
    // From the centre: the far side at t in [R − sagitta, R].
    const RayHit out = query.castRay(Eigen::Vector3d::Zero(), u);
    ASSERT_TRUE(out.hit);
    EXPECT_GE(out.t, radius - sagitta - 1e-12);
    EXPECT_LE(out.t, radius + 1e-12);
    EXPECT_GT(out.normal.dot(u), 0.9);
    // Tangent-ish ray that passes 1.5 R from the centre: a miss.
    const Eigen::Vector3d side = u.unitOrthogonal();
    EXPECT_FALSE(query.castRay(5.0 * u + 1.5 * side, -u).hit);
  }
}

TEST(MeshQuery, BadMeshesFailAndQueriesReturnNothing) {
  std::vector<std::pair<std::string, TriangleMesh>> bad;
  bad.emplace_back("no faces", TriangleMesh{});
  TriangleMesh nan_vertex = unitTriangle();
  nan_vertex.vertices[1].y() = std::nan("");
  bad.emplace_back("NaN vertex", nan_vertex);
  TriangleMesh inf_vertex = unitTriangle();
  inf_vertex.vertices[2].z() = kInf;
  bad.emplace_back("infinite vertex", inf_vertex);
  TriangleMesh index_high = unitTriangle();
  index_high.faces[0][2] = 3;
  bad.emplace_back("index past the end", index_high);
  TriangleMesh index_negative = unitTriangle();
  index_negative.faces[0][1] = -1;
  bad.emplace_back("negative index", index_negative);
  TriangleMesh flat = unitTriangle();
  flat.vertices[2] = {2.0, 0.0, 0.0};
  bad.emplace_back("zero area", flat);
  for (const auto& [name, mesh] : bad) {
    const MeshQuery query(mesh);
    EXPECT_FALSE(query.status().ok()) << name;
    EXPECT_FALSE(query.status().message.empty()) << name;
    EXPECT_FALSE(query.closest({0.1, 0.1, 0.1}).found) << name;
    const auto batch = query.closest(Points{{0.1, 0.1, 0.1}, {0.0, 0.0, 0.0}});
    ASSERT_EQ(batch.size(), 2u);
    EXPECT_FALSE(batch[0].found || batch[1].found) << name;
    EXPECT_FALSE(query.castRay({0.1, 0.1, 1.0}, {0.0, 0.0, -1.0}).hit) << name;
  }
  EXPECT_EQ(MeshQuery(TriangleMesh{}).status().code, StatusCode::kInvalidInput);
  EXPECT_EQ(MeshQuery(index_high).status().code, StatusCode::kInvalidInput);
  EXPECT_EQ(MeshQuery(flat).status().code, StatusCode::kDegenerateInput);
}

TEST(MeshQuery, NonFiniteQueriesFindNothing) {
  const MeshQuery query(unitTriangle());
  EXPECT_FALSE(query.closest({std::nan(""), 0.0, 0.0}).found);
  EXPECT_FALSE(query.closest({kInf, 0.0, 0.0}).found);
  EXPECT_FALSE(query.castRay({kInf, 0.0, 0.0}, {1.0, 0.0, 0.0}).hit);
  // Far beyond float range still works (every face is a candidate then).
  const ClosestPoint far = query.closest({0.25, 0.25, 1e35});
  ASSERT_TRUE(far.found);
  EXPECT_DOUBLE_EQ(far.signed_distance, 1e35);
}

TEST(MeshQuery, KeepsTheMeshWithFaceNormals) {
  const TriangleMesh box = test::makeBox(Eigen::Vector3d(1.0, 2.0, 3.0));
  const MeshQuery query(box);
  EXPECT_EQ(query.mesh().vertices, box.vertices);
  EXPECT_EQ(query.mesh().faces, box.faces);
  ASSERT_EQ(query.mesh().face_normals.size(), box.faces.size());
  for (int f = 0; f < static_cast<int>(box.faces.size()); ++f) {
    EXPECT_NEAR(
        (query.mesh().face_normals[static_cast<std::size_t>(f)] - faceNormal(box, f)).norm(),
        0.0,
        1e-15);
  }
}

}  // namespace
}  // namespace freeform_inspection
