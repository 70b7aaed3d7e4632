// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// Per-vertex curvature of a triangle mesh (paper §2.1): mean curvature from dihedral angles
// (eq. 3) or from the cotangent Laplacian (eq. 4–5, Meyer et al.), Gaussian curvature from the
// angle deficit (eq. 2). See docs/descriptors.md, "Curvature on meshes".
#include <array>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "freeform_inspection/curvature.h"
#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Per-vertex sums over faces and edges, normalised at the end.
struct VertexSums {
  explicit VertexSums(std::size_t n)
      : face_area(n, 0.0),
        angle(n, 0.0),
        edge_term(n, 0.0),
        mixed_area(n, 0.0),
        normal(n, Eigen::Vector3d::Zero()),
        laplacian(n, Eigen::Vector3d::Zero()) {}
  std::vector<double> face_area;   // A: total area of the faces around the vertex
  std::vector<double> angle;       // Σ θ_j, the corner angles at the vertex
  std::vector<double> edge_term;   // Σ |e| γ_e over the edges at the vertex
  std::vector<double> mixed_area;  // Meyer's A_mixed
  Points normal;                   // Σ face cross products: area-weighted normal direction
  Points laplacian;                // Σ (cot α + cot β)(x_i − x_j)
};

using Corners = std::array<Eigen::Vector3d, 3>;

std::size_t index(int i) {
  return static_cast<std::size_t>(i);
}

Status checkFaces(const Triangles& faces, std::size_t vertex_count) {
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const int v = faces[i][c];
      if (v < 0 || index(v) >= vertex_count) {
        return Status::failure(StatusCode::kInvalidInput,
                               "face " + std::to_string(i) + " has vertex index " +
                                   std::to_string(v) + " outside [0, " +
                                   std::to_string(vertex_count) + ")");
      }
    }
  }
  return Status::success();
}

Status checkFiniteCorners(const Points& vertices, const Triangles& faces) {
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      if (!vertices[index(faces[i][c])].allFinite()) {
        return Status::failure(StatusCode::kInvalidInput,
                               "vertex " + std::to_string(faces[i][c]) + " of face " +
                                   std::to_string(i) + " is not finite");
      }
    }
  }
  return Status::success();
}

bool inRange(int i, std::size_t size, bool allow_none) {
  return (allow_none && i == -1) || (i >= 0 && index(i) < size);
}

// The adjacency is trusted for topology but not for memory safety: one built for another mesh
// must give an error, never an out-of-bounds read.
Status checkAdjacency(const MeshAdjacency& adjacency, std::size_t vertices, std::size_t faces) {
  bool ok = adjacency.boundary_vertex.size() == vertices &&
            adjacency.vertex_face_offsets.size() == vertices + 1;
  for (std::size_t i = 0; ok && i < adjacency.edges.size(); ++i) {
    const MeshEdge& e = adjacency.edges[i];
    ok = inRange(e.v0, vertices, false) && inRange(e.v1, vertices, false) &&
         inRange(e.f0, faces, true) && inRange(e.f1, faces, true);
  }
  if (ok) {
    return Status::success();
  }
  return Status::failure(StatusCode::kInvalidInput,
                         "adjacency does not match the mesh (" + std::to_string(vertices) +
                             " vertices, " + std::to_string(faces) +
                             " faces): rebuild it with buildMeshAdjacency");
}

Status checkFacesAndCorners(const Points& vertices, const Triangles& faces) {
  const Status status = checkFaces(faces, vertices.size());
  return status.ok() ? checkFiniteCorners(vertices, faces) : status;
}

Corners cornersOf(const Points& vertices, const Eigen::Vector3i& f) {
  return {vertices[index(f[0])], vertices[index(f[1])], vertices[index(f[2])]};
}

// Interior angle at corner c; atan2 stays accurate near 0 and π, where acos does not.
double cornerAngle(const Corners& p, int c) {
  const Eigen::Vector3d u = p[index((c + 1) % 3)] - p[index(c)];
  const Eigen::Vector3d w = p[index((c + 2) % 3)] - p[index(c)];
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

// Meyer et al.'s mixed area: the Voronoi region inside non-obtuse triangles, and half or a
// quarter of the triangle in obtuse ones, where the circumcentre lies outside the triangle.
void addMixedArea(const Corners& p,
                  const Eigen::Vector3i& f,
                  const std::array<double, 3>& cot,
                  double area,
                  VertexSums& sums) {
  const bool obtuse = cot[0] < 0.0 || cot[1] < 0.0 || cot[2] < 0.0;
  for (int c = 0; c < 3; ++c) {
    const std::size_t i = index(c);
    const std::size_t j = index((c + 1) % 3);
    const std::size_t k = index((c + 2) % 3);
    double share = cot[i] < 0.0 ? area / 2.0 : area / 4.0;
    if (!obtuse) {
      share = ((p[i] - p[j]).squaredNorm() * cot[k] + (p[i] - p[k]).squaredNorm() * cot[j]) / 8.0;
    }
    sums.mixed_area[index(f[c])] += share;
  }
}

// eq. 4: the edge opposite corner c adds cot θ_c (x_j − x_k) to j and the reverse to k; summed
// over the two faces of an edge this is (cot α + cot β)(x_i − x_j).
void addCotangentTerms(const Corners& p,
                       const Eigen::Vector3i& f,
                       double cross_norm,
                       VertexSums& sums) {
  std::array<double, 3> cot{};
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector3d u = p[index((c + 1) % 3)] - p[index(c)];
    const Eigen::Vector3d w = p[index((c + 2) % 3)] - p[index(c)];
    cot[index(c)] = u.dot(w) / cross_norm;  // cos / sin, both scaled by |u||w|
  }
  for (int c = 0; c < 3; ++c) {
    const int j = (c + 1) % 3;
    const int k = (c + 2) % 3;
    const Eigen::Vector3d term = cot[index(c)] * (p[index(j)] - p[index(k)]);
    sums.laplacian[index(f[j])] += term;
    sums.laplacian[index(f[k])] -= term;
  }
  addMixedArea(p, f, cot, 0.5 * cross_norm, sums);
}

// Adds one face's area, angles and normal to its corners. Returns whether it has area.
bool addFace(const Points& vertices, const Eigen::Vector3i& f, bool cotangent, VertexSums& sums) {
  const Corners p = cornersOf(vertices, f);
  const Eigen::Vector3d cross = (p[1] - p[0]).cross(p[2] - p[0]);
  const double cross_norm = cross.norm();
  for (int c = 0; c < 3; ++c) {
    // Angles of zero-area faces still count: a collinear sliver closing a T-junction has a
    // corner of π that belongs in the angle sum of eq. 2.
    sums.angle[index(f[c])] += cornerAngle(p, c);
    sums.face_area[index(f[c])] += 0.5 * cross_norm;
    sums.normal[index(f[c])] += cross;
  }
  if (cotangent && cross_norm > 0.0) {
    addCotangentTerms(p, f, cross_norm, sums);
  }
  return cross_norm > 0.0;
}

// Returns the number of faces with non-zero area.
std::size_t addFaces(const Points& vertices,
                     const Triangles& faces,
                     const MeshCurvatureConfig& config,
                     VertexSums& sums) {
  const bool cotangent = config.method == MeanCurvatureMethod::kCotangent;
  std::size_t with_area = 0;
  for (const auto& f : faces) {
    with_area += addFace(vertices, f, cotangent, sums) ? 1 : 0;
  }
  return with_area;
}

// +1 when face f runs from a to b, −1 when from b to a, 0 when it lacks the edge.
int traversal(const Eigen::Vector3i& f, int a, int b) {
  for (int c = 0; c < 3; ++c) {
    if (f[c] == a) {
      return f[(c + 1) % 3] == b ? 1 : (f[(c + 2) % 3] == b ? -1 : 0);
    }
  }
  return 0;
}

// eq. 3: |e| γ_e with γ_e the signed dihedral angle, the rotation from n0 to n1 about the edge
// as face f0 runs along it; positive on convex edges (the surface bends away from the normal).
double edgeTerm(const Points& vertices,
                const Triangles& faces,
                const Points& face_normals,
                const MeshEdge& e) {
  if (e.f0 < 0 || e.f1 < 0) {
    return 0.0;  // boundary edge: one face, no dihedral angle
  }
  const int direction = traversal(faces[index(e.f0)], e.v0, e.v1);
  const Eigen::Vector3d edge = vertices[index(e.v1)] - vertices[index(e.v0)];
  const double length = edge.norm();
  if (direction == 0 || length == 0.0) {
    return 0.0;
  }
  const Eigen::Vector3d& n0 = face_normals[index(e.f0)];
  const Eigen::Vector3d& n1 = face_normals[index(e.f1)];
  const double sine = n0.cross(n1).dot(edge) * direction / length;
  return length * std::atan2(sine, n0.dot(n1));
}

void addEdges(const Points& vertices,
              const Triangles& faces,
              const MeshAdjacency& adjacency,
              VertexSums& sums) {
  const Points face_normals = computeFaceNormals(vertices, faces);
  for (const MeshEdge& e : adjacency.edges) {
    const double term = edgeTerm(vertices, faces, face_normals, e);
    sums.edge_term[index(e.v0)] += term;
    sums.edge_term[index(e.v1)] += term;
  }
}

Eigen::Vector3d unitOrZero(const Eigen::Vector3d& v) {
  const double length = v.norm();
  return length > 0.0 ? Eigen::Vector3d(v / length) : Eigen::Vector3d::Zero();
}

// eq. 4–5: H = |Δx| / 2 with Δx the Laplacian over the mixed area, signed by the normal. At
// boundary vertices Δx also holds the in-plane turning of the boundary curve, which is not
// mean curvature, so only its normal component is used there.
double cotangentMean(const VertexSums& sums,
                     const Eigen::Vector3d& normal,
                     std::size_t v,
                     bool boundary) {
  if (sums.mixed_area[v] <= 0.0) {
    return 0.0;
  }
  const Eigen::Vector3d laplacian = sums.laplacian[v] / (2.0 * sums.mixed_area[v]);
  if (boundary) {
    return 0.5 * laplacian.dot(normal);
  }
  return (laplacian.dot(normal) < 0.0 ? -0.5 : 0.5) * laplacian.norm();
}

// Fills the result for vertex v from the sums. Areas are A/3 (barycentric), the normalisation
// of eq. 2 and eq. 3, so the areas of all vertices add up to the surface area exactly.
void finishVertex(const VertexSums& sums,
                  const MeshAdjacency& adjacency,
                  const MeshCurvatureConfig& config,
                  std::size_t v,
                  CurvatureResult& result) {
  const double area = sums.face_area[v] / 3.0;
  const bool boundary = adjacency.boundary_vertex[v];
  result.area[v] = area;
  result.normals[v] = unitOrZero(sums.normal[v]);
  if (area <= 0.0) {
    return;  // no face with area: H = K = 0
  }
  // eq. 2: angle deficit; π on the boundary, where a flat neighbourhood is a half-disc.
  const double full_angle = boundary ? kPi : 2.0 * kPi;
  result.gaussian[v] = (full_angle - sums.angle[v]) / area;
  if (config.method == MeanCurvatureMethod::kCotangent) {
    result.mean[v] = cotangentMean(sums, result.normals[v], v, boundary);
  } else {
    result.mean[v] = 0.25 * sums.edge_term[v] / area;  // eq. 3
  }
}

}  // namespace

CurvatureResult computeMeshCurvature(const Points& vertices,
                                     const Triangles& faces,
                                     const MeshAdjacency& adjacency,
                                     const MeshCurvatureConfig& config) {
  CurvatureResult result;
  result.status = checkFacesAndCorners(vertices, faces);
  if (!result.status.ok()) {
    return result;
  }
  const std::size_t n = vertices.size();
  result.mean.assign(n, 0.0);
  result.gaussian.assign(n, 0.0);
  result.area.assign(n, 0.0);
  result.normals.assign(n, Eigen::Vector3d::Zero());
  VertexSums sums(n);
  if (addFaces(vertices, faces, config, sums) == 0) {
    result.status =
        Status::failure(StatusCode::kDegenerateInput,
                        "mesh has no face with non-zero area (" + std::to_string(faces.size()) +
                            " faces, " + std::to_string(n) + " vertices)");
    return result;
  }
  const Status adjacency_status = checkAdjacency(adjacency, n, faces.size());
  if (!adjacency_status.ok()) {
    return CurvatureResult{adjacency_status, {}, {}, {}, {}, {}};
  }
  addEdges(vertices, faces, adjacency, sums);
  for (std::size_t v = 0; v < n; ++v) {
    finishVertex(sums, adjacency, config, v, result);
  }
  return result;
}

}  // namespace freeform_inspection
