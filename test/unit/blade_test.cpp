// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// The parametric blade generator and the sample part it ships in data/blade/.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "blade_geometry.h"
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh.h"

#ifndef FREEFORM_DATA_DIR
#error "FREEFORM_DATA_DIR must be defined as the absolute path of the package's data directory"
#endif

namespace freeform_inspection {
namespace tools {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMetresPerMillimetre = 0.001;
constexpr double kScanNoiseSigmaM = 0.02e-3;  // what generate_blade adds along the normal
// 5 sigma, plus slack for the float32 coordinates of the STL (~1e-8 m at 0.14 m).
constexpr double kOnSurfaceToleranceM = 5.0 * kScanNoiseSigmaM + 1e-6;
constexpr double kMinAngleBoundDeg = 4.0;  // measured: 4.43 standard, 4.26 fine
constexpr double kMinAreaBoundMm2 = 1e-4;  // far above float32 rounding of the STL

std::string bladeFile(const std::string& name) {
  return std::string(FREEFORM_DATA_DIR) + "/blade/" + name;
}

const Eigen::Vector3d& corner(const TriangleMesh& mesh, const Eigen::Vector3i& face, int c) {
  return mesh.vertices[static_cast<std::size_t>(face[c])];
}

double minAngleDeg(const TriangleMesh& mesh) {
  double min_angle = 180.0;
  for (const auto& f : mesh.faces) {
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d a = corner(mesh, f, (c + 1) % 3) - corner(mesh, f, c);
      const Eigen::Vector3d b = corner(mesh, f, (c + 2) % 3) - corner(mesh, f, c);
      min_angle = std::min(min_angle, std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / kPi);
    }
  }
  return min_angle;
}

double minArea(const TriangleMesh& mesh) {
  double min_area = std::numeric_limits<double>::infinity();
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d n =
        (corner(mesh, f, 1) - corner(mesh, f, 0)).cross(corner(mesh, f, 2) - corner(mesh, f, 0));
    min_area = std::min(min_area, 0.5 * n.norm());
  }
  return min_area;
}

// Closest point on triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& p,
                                  const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    return a;
  }
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) {
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    return a + d1 / (d1 - d3) * ab;
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) {
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    return a + d2 / (d2 - d6) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Brute-force point-to-mesh distance. A bounding-sphere test per face in plain doubles skips
// most faces, so that the few hundred queries stay fast even in an unoptimised build.
class MeshDistance {
 public:
  struct Closest {
    double distance = std::numeric_limits<double>::infinity();
    std::size_t face = 0;
  };

  explicit MeshDistance(const TriangleMesh& mesh) : mesh_(mesh) {
    for (const auto& f : mesh.faces) {
      const Eigen::Vector3d centre =
          (corner(mesh, f, 0) + corner(mesh, f, 1) + corner(mesh, f, 2)) / 3.0;
      double radius = 0.0;
      for (int c = 0; c < 3; ++c) {
        radius = std::max(radius, (corner(mesh, f, c) - centre).norm());
      }
      spheres_.push_back({centre.x(), centre.y(), centre.z(), radius});
    }
  }

  // Starts from the face with the nearest centre, so that the sphere test prunes from the start.
  Closest operator()(const Eigen::Vector3d& p) const {
    const std::vector<double> squared = squaredCentreDistances(p);
    const auto nearest = static_cast<std::size_t>(std::min_element(squared.begin(), squared.end()) -
                                                  squared.begin());
    Closest best{distanceToFace(p, nearest), nearest};
    for (std::size_t i = 0; i < spheres_.size(); ++i) {
      const double reach = best.distance + spheres_[i].radius;
      if (squared[i] < reach * reach && distanceToFace(p, i) < best.distance) {
        best = Closest{distanceToFace(p, i), i};
      }
    }
    return best;
  }

 private:
  struct Sphere {
    double x, y, z, radius;
  };

  std::vector<double> squaredCentreDistances(const Eigen::Vector3d& p) const {
    const double px = p.x(), py = p.y(), pz = p.z();
    std::vector<double> squared(spheres_.size());
    for (std::size_t i = 0; i < spheres_.size(); ++i) {
      const double dx = px - spheres_[i].x, dy = py - spheres_[i].y, dz = pz - spheres_[i].z;
      squared[i] = dx * dx + dy * dy + dz * dz;
    }
    return squared;
  }

  double distanceToFace(const Eigen::Vector3d& p, std::size_t face) const {
    const auto& f = mesh_.faces[face];
    return (p - closestOnTriangle(p, corner(mesh_, f, 0), corner(mesh_, f, 1), corner(mesh_, f, 2)))
        .norm();
  }

  const TriangleMesh& mesh_;
  std::vector<Sphere> spheres_;
};

struct Segment {
  double ax, ay, bx, by;
};

int orientation(double px, double py, double qx, double qy, double rx, double ry) {
  const double z = (qx - px) * (ry - py) - (qy - py) * (rx - px);
  return (z > 0.0) - (z < 0.0);
}

// Closed segments intersect (touching counts); plain doubles keep the O(n^2) loop fast.
bool segmentsCross(const Segment& s, const Segment& t) {
  if (std::max(s.ax, s.bx) < std::min(t.ax, t.bx) || std::max(t.ax, t.bx) < std::min(s.ax, s.bx) ||
      std::max(s.ay, s.by) < std::min(t.ay, t.by) || std::max(t.ay, t.by) < std::min(s.ay, s.by)) {
    return false;
  }
  return orientation(s.ax, s.ay, s.bx, s.by, t.ax, t.ay) *
                 orientation(s.ax, s.ay, s.bx, s.by, t.bx, t.by) <=
             0 &&
         orientation(t.ax, t.ay, t.bx, t.by, s.ax, s.ay) *
                 orientation(t.ax, t.ay, t.bx, t.by, s.bx, s.by) <=
             0;
}

// Non-adjacent edges of a simple polygon neither cross nor touch.
bool isSimplePolygon(const std::vector<Eigen::Vector2d>& polygon) {
  const std::size_t n = polygon.size();
  std::vector<Segment> edges;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % n];
    edges.push_back({a.x(), a.y(), b.x(), b.y()});
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 2; j < n; ++j) {
      if ((j + 1) % n != i && segmentsCross(edges[i], edges[j])) {
        return false;
      }
    }
  }
  return true;
}

// Direction of the chord (leading to trailing edge) of section k, in the xy plane.
Eigen::Vector2d chordVector(const TriangleMesh& mesh, const BladeLayout& layout, int k) {
  const auto at = [&](int point) {
    return mesh.vertices[static_cast<std::size_t>(k * layout.points_per_section + point)];
  };
  return (at(layout.trailing_edge_point) - at(layout.leading_edge_point)).head<2>();
}

double angleDeg(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  return std::atan2(from.x() * to.y() - from.y() * to.x(), from.dot(to)) * 180.0 / kPi;
}

void expectClosedGenusZeroSolid(const TriangleMesh& mesh) {
  const MeshTopology topology = analyzeTopology(mesh);
  EXPECT_TRUE(topology.isOutwardSolid());
  EXPECT_EQ(topology.boundary_edges, 0u);
  EXPECT_EQ(topology.non_manifold_edges, 0u);
  EXPECT_EQ(topology.misoriented_edges, 0u);
  EXPECT_EQ(topology.degenerate_faces, 0u);
  EXPECT_EQ(topology.unused_vertices, 0u);
  // Euler characteristic 2 of a closed triangulated sphere: F = 2V - 4.
  EXPECT_EQ(mesh.faces.size(), 2 * mesh.vertices.size() - 4);
}

bool readMatrix(const std::string& path, Eigen::Matrix4d& matrix) {
  std::ifstream in(path);
  for (int i = 0; i < 16; ++i) {
    in >> matrix(i / 4, i % 4);
  }
  return static_cast<bool>(in);
}

// Every 100th point of the shipped scan (300 of 30,000) and its normal.
Scan loadScanSubsample() {
  const ScanLoadResult loaded = loadScan(bladeFile("blade_scan.ply"), 1.0);
  EXPECT_TRUE(loaded.status.ok()) << loaded.status.message;
  Scan subsample;
  for (std::size_t i = 0; i < loaded.scan.points.size(); i += 100) {
    subsample.points.push_back(loaded.scan.points[i]);
    subsample.normals.push_back(loaded.scan.normals.empty() ? Eigen::Vector3d::Zero()
                                                            : loaded.scan.normals[i]);
  }
  return subsample;
}

TriangleMesh loadShippedMesh(const std::string& name) {
  const MeshLoadResult loaded = loadMesh(bladeFile(name), kMetresPerMillimetre);
  EXPECT_TRUE(loaded.status.ok()) << name << ": " << loaded.status.message;
  return loaded.mesh;
}

const TriangleMesh& fineCad() {
  static const TriangleMesh cad = loadShippedMesh("blade_fine.stl");
  return cad;
}

// Distances [m] from the transformed scan points to the fine CAD surface.
std::vector<double> distancesToCad(const Scan& scan, const Eigen::Matrix4d& T_cad_scan) {
  const MeshDistance distance(fineCad());
  const Eigen::Isometry3d transform(T_cad_scan);
  std::vector<double> distances;
  for (const auto& p : scan.points) {
    distances.push_back(distance(transform * p).distance);
  }
  return distances;
}

double fractionBelow(const std::vector<double>& values, double limit) {
  const auto below =
      std::count_if(values.begin(), values.end(), [limit](double v) { return v <= limit; });
  return static_cast<double>(below) / static_cast<double>(values.size());
}

TEST(BladeGeometry, StandardBladeIsClosedOutwardGenusZeroSolid) {
  const TriangleMesh mesh = generateBlade(BladeParameters());
  expectClosedGenusZeroSolid(mesh);
  EXPECT_GE(mesh.vertices.size(), 6000u);
  EXPECT_LE(mesh.vertices.size(), 8500u);
  EXPECT_EQ(mesh.face_normals.size(), mesh.faces.size());
}

TEST(BladeGeometry, FineBladeIsClosedOutwardGenusZeroSolid) {
  const TriangleMesh mesh = generateBlade(fineBladeParameters());
  expectClosedGenusZeroSolid(mesh);
  EXPECT_GE(mesh.vertices.size(), 25000u);
  EXPECT_LE(mesh.vertices.size(), 35000u);
}

// The platform is the widest part, so x and y come from the rotated superellipse: at least the
// extent of its sampled axis points, at most that of its rotated bounding rectangle.
TEST(BladeGeometry, BoundingBoxMatchesParameters) {
  const BladeParameters p;
  const BoundingBox box = computeBoundingBox(generateBlade(p).vertices);
  const double a = p.platform_length_mm, b = p.platform_width_mm;
  const double cos_angle = std::cos(p.platform_angle_deg * kPi / 180.0);
  const double sin_angle = std::sin(p.platform_angle_deg * kPi / 180.0);
  const Eigen::Vector3d extent = box.extent();
  EXPECT_GE(extent.x(), a * cos_angle - 1e-9);
  EXPECT_LE(extent.x(), a * cos_angle + b * sin_angle);
  EXPECT_GE(extent.y(), b * cos_angle - 1e-9);
  EXPECT_LE(extent.y(), b * cos_angle + a * sin_angle);
  EXPECT_NEAR(box.min.z(), 0.0, 1e-12);
  EXPECT_NEAR(extent.z(), p.platform_height_mm + p.fillet_height_mm + p.span_mm, 1e-9);
}

TEST(BladeGeometry, TrianglesAreWellShaped) {
  for (const BladeParameters& p : {BladeParameters(), fineBladeParameters()}) {
    const TriangleMesh mesh = generateBlade(p);
    const double min_angle = minAngleDeg(mesh);
    std::cout << "blade with " << mesh.vertices.size() << " vertices: min angle " << min_angle
              << " deg, min area " << minArea(mesh) << " mm^2\n";
    EXPECT_GT(min_angle, kMinAngleBoundDeg);
    EXPECT_GT(minArea(mesh), kMinAreaBoundMm2);
  }
}

TEST(BladeGeometry, TipIsTwistedByTheParameterisedStaggerAndChordsMatch) {
  BladeParameters other_twist;
  other_twist.root_stagger_deg = -5.0;
  other_twist.tip_stagger_deg = 25.0;
  for (const BladeParameters& p : {BladeParameters(), other_twist}) {
    const TriangleMesh mesh = generateBlade(p);
    const BladeLayout layout = bladeLayout(p);
    const int tip = static_cast<int>(layout.section_z_mm.size()) - 1;
    const Eigen::Vector2d root_chord = chordVector(mesh, layout, layout.root_section);
    const Eigen::Vector2d tip_chord = chordVector(mesh, layout, tip);
    EXPECT_NEAR(angleDeg(root_chord, tip_chord), p.tip_stagger_deg - p.root_stagger_deg, 1.0);
    EXPECT_NEAR(angleDeg(Eigen::Vector2d::UnitX(), root_chord), p.root_stagger_deg, 1.0);
    EXPECT_NEAR(root_chord.norm(), p.root_chord_mm, 1e-9);
    EXPECT_NEAR(tip_chord.norm(), p.tip_chord_mm, 1e-9);
  }
}

TEST(BladeGeometry, EverySectionIsASimplePolygon) {
  for (const BladeParameters& p : {BladeParameters(), fineBladeParameters()}) {
    for (const double z : bladeLayout(p).section_z_mm) {
      EXPECT_TRUE(isSimplePolygon(sectionOutline(p, z))) << "section at z = " << z << " mm";
    }
  }
}

TEST(BladeGeometry, InvalidParametersAreRejected) {
  EXPECT_TRUE(validateBladeParameters(BladeParameters()).ok());
  BladeParameters p;
  p.chord_stations = 3;
  EXPECT_EQ(validateBladeParameters(p).code, StatusCode::kInvalidInput);
  EXPECT_TRUE(generateBlade(p).faces.empty());
  p = BladeParameters();
  p.tip_chord_mm = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(validateBladeParameters(p).message.find("tip_chord_mm"), std::string::npos);
  p = BladeParameters();
  p.camber_position = 1.0;
  EXPECT_FALSE(validateBladeParameters(p).ok());
}

TEST(BladeGeometry, GenerationIsDeterministic) {
  const TriangleMesh first = generateBlade(BladeParameters());
  const TriangleMesh second = generateBlade(BladeParameters());
  ASSERT_EQ(first.vertices.size(), second.vertices.size());
  EXPECT_TRUE(std::equal(first.vertices.begin(), first.vertices.end(), second.vertices.begin()));
  EXPECT_TRUE(std::equal(first.faces.begin(), first.faces.end(), second.faces.begin()));
}

TEST(ShippedBlade, StlFilesAreWhatTheGeneratorMakesToday) {
  const std::pair<const char*, BladeParameters> files[] = {
      {"blade.stl", BladeParameters()}, {"blade_fine.stl", fineBladeParameters()}};
  for (const auto& file : files) {
    const TriangleMesh shipped = loadShippedMesh(file.first);
    const TriangleMesh generated = generateBlade(file.second);
    expectClosedGenusZeroSolid(shipped);
    EXPECT_EQ(shipped.vertices.size(), generated.vertices.size()) << file.first;
    EXPECT_EQ(shipped.faces.size(), generated.faces.size()) << file.first;
    const double diagonal = computeBoundingBox(shipped.vertices).diagonal();
    EXPECT_GT(diagonal, 0.15) << file.first << " is not in millimetres";
    EXPECT_LT(diagonal, 0.17) << file.first << " is not in millimetres";
    EXPECT_NEAR(
        diagonal, kMetresPerMillimetre * computeBoundingBox(generated.vertices).diagonal(), 1e-6);
  }
}

TEST(ShippedBlade, TransformFileIsRigidInMetres) {
  Eigen::Matrix4d T_cad_scan;
  ASSERT_TRUE(readMatrix(bladeFile("blade_scan_T_cad_scan.txt"), T_cad_scan));
  const Eigen::Matrix3d rotation = T_cad_scan.topLeftCorner<3, 3>();
  EXPECT_TRUE((rotation * rotation.transpose()).isIdentity(1e-12));
  EXPECT_NEAR(rotation.determinant(), 1.0, 1e-12);
  EXPECT_TRUE(T_cad_scan.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1)));
  const Eigen::Vector3d translation = T_cad_scan.topRightCorner<3, 1>();
  EXPECT_NEAR(translation.norm(), 0.2, 1e-9);  // inverting keeps the length of the translation
  EXPECT_GT(Eigen::AngleAxisd(rotation).angle(), 0.5);
}

TEST(ShippedBlade, ScanLiesOnTheCadSurfaceAfterTheShippedTransform) {
  const Scan scan = loadScanSubsample();
  ASSERT_EQ(scan.points.size(), 300u);
  ASSERT_FALSE(fineCad().faces.empty());
  Eigen::Matrix4d T_cad_scan;
  ASSERT_TRUE(readMatrix(bladeFile("blade_scan_T_cad_scan.txt"), T_cad_scan));
  const std::vector<double> distances = distancesToCad(scan, T_cad_scan);
  EXPECT_GE(fractionBelow(distances, kOnSurfaceToleranceM), 0.99);
  double sum_squares = 0.0;
  for (const double d : distances) {
    sum_squares += d * d;
  }
  // The noise really is sigma = 0.02 mm: catches a scan written in the wrong unit.
  const double rms = std::sqrt(sum_squares / static_cast<double>(distances.size()));
  std::cout << "scan subsample: " << 100.0 * fractionBelow(distances, kOnSurfaceToleranceM)
            << " % within " << kOnSurfaceToleranceM * 1e3 << " mm, rms " << rms * 1e3 << " mm\n";
  EXPECT_GT(rms, 0.7 * kScanNoiseSigmaM);
  EXPECT_LT(rms, 1.3 * kScanNoiseSigmaM);
}

// Normals must be rotated with the points and point out of the material: compared with the
// normal of the closest CAD face (a few points near edges may pick a neighbouring face).
TEST(ShippedBlade, ScanNormalsAgreeWithTheCadAfterTheShippedTransform) {
  const Scan scan = loadScanSubsample();
  ASSERT_EQ(scan.normals.size(), 300u);
  ASSERT_FALSE(fineCad().faces.empty());
  Eigen::Matrix4d T_cad_scan;
  ASSERT_TRUE(readMatrix(bladeFile("blade_scan_T_cad_scan.txt"), T_cad_scan));
  const Eigen::Isometry3d transform(T_cad_scan);
  const MeshDistance distance(fineCad());
  std::size_t agreeing = 0;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    const std::size_t face = distance(transform * scan.points[i]).face;
    const Eigen::Vector3d normal = transform.linear() * scan.normals[i];
    agreeing += normal.dot(fineCad().face_normals[face]) > 0.9 ? 1 : 0;
  }
  EXPECT_GE(static_cast<double>(agreeing), 0.95 * static_cast<double>(scan.points.size()));
}

TEST(ShippedBlade, IdentityInsteadOfTheShippedTransformLeavesTheScanFar) {
  const Scan scan = loadScanSubsample();
  ASSERT_EQ(scan.points.size(), 300u);
  ASSERT_FALSE(fineCad().faces.empty());
  const std::vector<double> distances = distancesToCad(scan, Eigen::Matrix4d::Identity());
  EXPECT_LT(fractionBelow(distances, kOnSurfaceToleranceM), 0.01);
}

}  // namespace
}  // namespace tools
}  // namespace freeform_inspection
