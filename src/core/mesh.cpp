// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/mesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <unordered_map>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace freeform_inspection {
namespace {

// Hash of the exact bit pattern: welding joins only corners that the file stored identically,
// so no tolerance can merge distinct CAD vertices of a fine mesh.
struct ExactPointHash {
  std::size_t operator()(const Eigen::Vector3d& p) const {
    std::size_t h = 1469598103934665603ull;
    for (int i = 0; i < 3; ++i) {
      h ^= std::hash<double>()(p[i]) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    }
    return h;
  }
};

struct ExactPointEqual {
  bool operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    return a.x() == b.x() && a.y() == b.y() && a.z() == b.z();
  }
};

std::uint64_t edgeKey(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (hi << 32) | lo;
}

// Per undirected edge: how many faces use it, and how many traverse it from low to high index.
struct EdgeUse {
  int faces = 0;
  int forward = 0;
};

bool isDegenerate(const Eigen::Vector3i& f, const Points& v) {
  if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) {
    return true;
  }
  return (v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]).squaredNorm() == 0.0;
}

}  // namespace

BoundingBox computeBoundingBox(const Points& points) {
  BoundingBox box;
  if (points.empty()) {
    return box;
  }
  box.min = box.max = points.front();
  for (const auto& p : points) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

double principalThickness(const TriangleMesh& mesh) {
  double total = 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  // The surface's exact moments: over a triangle (a, b, c) of area A, ∫x dA = A s / 3 and
  // ∫x xᵀ dA = A (a aᵀ + b bᵀ + c cᵀ + s sᵀ) / 12, s = a + b + c.
  for (const Eigen::Vector3i& face : mesh.faces) {
    const double area = triangleArea(mesh.vertices, face);
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(face[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(face[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(face[2])];
    const Eigen::Vector3d sum = a + b + c;
    total += area;
    mean += area / 3.0 * sum;
    second += area / 12.0 *
              (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
  }
  if (!(total > 0.0)) {
    return 0.0;
  }
  mean /= total;
  const Eigen::Matrix3d covariance = second / total - mean * mean.transpose();
  // Eigenvalues ascending: column 0 is the axis of least spread.
  const Eigen::Vector3d axis =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(0);
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : mesh.vertices) {
    low = std::min(low, v.dot(axis));
    high = std::max(high, v.dot(axis));
  }
  return high - low;
}

double triangleArea(const Points& vertices, const Eigen::Vector3i& face) {
  const Eigen::Vector3d& a = vertices[static_cast<std::size_t>(face[0])];
  return 0.5 * (vertices[static_cast<std::size_t>(face[1])] - a)
                   .cross(vertices[static_cast<std::size_t>(face[2])] - a)
                   .norm();
}

Points computeFaceNormals(const Points& vertices, const Triangles& faces) {
  Points normals;
  normals.reserve(faces.size());
  for (const auto& f : faces) {
    const Eigen::Vector3d n =
        (vertices[f[1]] - vertices[f[0]]).cross(vertices[f[2]] - vertices[f[0]]);
    const double length = n.norm();
    normals.push_back(length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero());
  }
  return normals;
}

TriangleMesh weldTriangleSoup(const Points& corners) {
  TriangleMesh mesh;
  std::unordered_map<Eigen::Vector3d, int, ExactPointHash, ExactPointEqual> index;
  index.reserve(corners.size() / 2);
  const std::size_t triangles = corners.size() / 3;
  mesh.faces.reserve(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    Eigen::Vector3i face;
    for (int c = 0; c < 3; ++c) {
      const auto& p = corners[3 * t + static_cast<std::size_t>(c)];
      const auto inserted = index.emplace(p, static_cast<int>(mesh.vertices.size()));
      if (inserted.second) {
        mesh.vertices.push_back(p);
      }
      face[c] = inserted.first->second;
    }
    if (face[0] != face[1] && face[1] != face[2] && face[0] != face[2]) {
      mesh.faces.push_back(face);
    }
  }
  mesh.face_normals = computeFaceNormals(mesh.vertices, mesh.faces);
  return mesh;
}

MeshTopology analyzeTopology(const TriangleMesh& mesh) {
  MeshTopology topology;
  std::unordered_map<std::uint64_t, EdgeUse> edges;
  edges.reserve(mesh.faces.size() * 2);
  std::vector<bool> used(mesh.vertices.size(), false);
  for (const auto& f : mesh.faces) {
    if (isDegenerate(f, mesh.vertices)) {
      ++topology.degenerate_faces;
    }
    const Eigen::Vector3d& a = mesh.vertices[f[0]];
    const Eigen::Vector3d& b = mesh.vertices[f[1]];
    const Eigen::Vector3d& c = mesh.vertices[f[2]];
    topology.signed_volume += a.dot(b.cross(c)) / 6.0;  // divergence theorem, tetra to origin
    topology.area += triangleArea(mesh.vertices, f);
    for (int i = 0; i < 3; ++i) {
      const int from = f[i];
      const int to = f[(i + 1) % 3];
      used[static_cast<std::size_t>(from)] = true;
      EdgeUse& use = edges[edgeKey(from, to)];
      ++use.faces;
      use.forward += from < to ? 1 : 0;
    }
  }
  topology.edges = edges.size();
  for (const auto& entry : edges) {
    const EdgeUse& use = entry.second;
    if (use.faces == 1) {
      ++topology.boundary_edges;
    } else if (use.faces > 2) {
      ++topology.non_manifold_edges;
    } else if (use.forward != 1) {
      ++topology.misoriented_edges;
    }
  }
  topology.unused_vertices = static_cast<std::size_t>(std::count(used.begin(), used.end(), false));
  return topology;
}

namespace {

// One refinement pass: returns false when no edge was longer than max_edge.
bool splitLongEdges(TriangleMesh* mesh, double max_edge) {
  std::unordered_map<std::uint64_t, int> midpoint;
  const double max2 = max_edge * max_edge;
  for (const auto& f : mesh->faces) {
    for (int e = 0; e < 3; ++e) {
      const int a = f[e];
      const int b = f[(e + 1) % 3];
      const auto& pa = mesh->vertices[static_cast<std::size_t>(a)];
      const auto& pb = mesh->vertices[static_cast<std::size_t>(b)];
      if ((pa - pb).squaredNorm() > max2 && midpoint.count(edgeKey(a, b)) == 0) {
        midpoint[edgeKey(a, b)] = static_cast<int>(mesh->vertices.size());
        mesh->vertices.push_back(0.5 * (pa + pb));
      }
    }
  }
  if (midpoint.empty()) {
    return false;
  }
  Triangles faces;
  faces.reserve(mesh->faces.size() * 2);
  for (const auto& f : mesh->faces) {
    int m[3];
    int split = 0;
    for (int e = 0; e < 3; ++e) {
      const auto found = midpoint.find(edgeKey(f[e], f[(e + 1) % 3]));
      m[e] = found == midpoint.end() ? -1 : found->second;
      split += m[e] >= 0 ? 1 : 0;
    }
    if (split == 0) {
      faces.push_back(f);
    } else if (split == 3) {
      faces.emplace_back(f[0], m[0], m[2]);
      faces.emplace_back(m[0], f[1], m[1]);
      faces.emplace_back(m[2], m[1], f[2]);
      faces.emplace_back(m[0], m[1], m[2]);
    } else {
      // Rotate so the (first) split edge is edge 0: corners c0 c1 c2, midpoint m0 on c0–c1.
      int r = 0;
      while (m[r] < 0) {
        ++r;
      }
      if (split == 2 && m[(r + 2) % 3] >= 0) {
        r = (r + 2) % 3;  // the two split edges are r and r+1
      }
      const int c0 = f[r];
      const int c1 = f[(r + 1) % 3];
      const int c2 = f[(r + 2) % 3];
      const int m0 = m[r];
      const int m1 = m[(r + 1) % 3];
      if (split == 1) {
        faces.emplace_back(c0, m0, c2);
        faces.emplace_back(m0, c1, c2);
      } else {  // edges c0–c1 (m0) and c1–c2 (m1) split
        faces.emplace_back(c0, m0, c2);
        faces.emplace_back(m0, c1, m1);
        faces.emplace_back(m0, m1, c2);
      }
    }
  }
  mesh->faces = std::move(faces);
  return true;
}

}  // namespace

TriangleMesh refineLongEdges(const TriangleMesh& mesh, double max_edge, std::size_t max_faces) {
  TriangleMesh refined = mesh;
  if (max_edge > 0.0) {
    // Each pass at most quadruples the faces: stop before a pass could exceed the cap.
    while (refined.faces.size() * 4 <= max_faces && splitLongEdges(&refined, max_edge)) {
    }
  }
  refined.face_normals = computeFaceNormals(refined.vertices, refined.faces);
  return refined;
}

}  // namespace freeform_inspection
