// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/chord_error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include <Eigen/Geometry>

#include "freeform_inspection/mesh.h"
#include "freeform_inspection/mesh_adjacency.h"

namespace freeform_inspection {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;
// Faces whose normals lie within this of a facet's first face belong to that flat facet (the
// two triangles of a cylinder's quad; rounding in the file's coordinates turns them by less).
const double kPlanarCos = std::cos(0.5 * kDegree);
// Turns of this much or more are drawn edges: exporters' angle tolerances stay below it, and a
// coarser curve is no longer a curve to the scan's eye.
constexpr double kCreaseRad = 60.0 * kDegree;
// Facets of one tessellated curve have comparable widths across their shared edge; a flat face
// beside a fillet's narrow facets is not one of them.
constexpr double kWidthRatio = 3.0;
// Two turns of a facet lie on opposite sides when their outward directions are more than ~105°
// apart (120° for a triangle's three sides, 180° for a quad's opposite ones).
constexpr double kOppositeCos = -0.25;

std::uint64_t pairKey(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::max(a, b)));
}

// Flat facets: faces grown from each unassigned face, in index order, across shared edges, while
// their normals stay within kPlanarCos of the first face's.
struct Facets {
  std::vector<int> of_face;  // -1 for faces without a normal
  std::vector<Eigen::Vector3d> normal;
  std::vector<Eigen::Vector3d> centroid;
  std::vector<std::vector<int>> vertices;  // on its border: where its extents are reached
};

Facets growFacets(const TriangleMesh& mesh,
                  const Points& normals,
                  const MeshAdjacency& adjacency,
                  const std::vector<std::array<int, 3>>& face_edges) {
  Facets facets;
  const std::size_t faces = mesh.faces.size();
  facets.of_face.assign(faces, -1);
  std::vector<int> queue;
  for (std::size_t seed = 0; seed < faces; ++seed) {
    if (facets.of_face[seed] >= 0 || normals[seed].isZero()) {
      continue;
    }
    const int id = static_cast<int>(facets.normal.size());
    const Eigen::Vector3d& n = normals[seed];
    facets.normal.push_back(n);
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    double total = 0.0;
    facets.of_face[seed] = id;
    queue.assign(1, static_cast<int>(seed));
    while (!queue.empty()) {
      const auto f = static_cast<std::size_t>(queue.back());
      queue.pop_back();
      const Eigen::Vector3i& corners = mesh.faces[f];
      const double a = triangleArea(mesh.vertices, corners);
      for (int c = 0; c < 3; ++c) {
        weighted += a * mesh.vertices[static_cast<std::size_t>(corners[c])] / 3.0;
      }
      total += a;
      for (const int e : face_edges[f]) {
        if (e < 0) {
          continue;
        }
        const MeshEdge& edge = adjacency.edges[static_cast<std::size_t>(e)];
        const int other = edge.f0 == static_cast<int>(f) ? edge.f1 : edge.f0;
        if (other < 0 || facets.of_face[static_cast<std::size_t>(other)] >= 0 ||
            !(normals[static_cast<std::size_t>(other)].dot(n) >= kPlanarCos)) {
          continue;
        }
        facets.of_face[static_cast<std::size_t>(other)] = id;
        queue.push_back(other);
      }
    }
    facets.centroid.push_back(total > 0.0 ? Eigen::Vector3d(weighted / total)
                                          : mesh.vertices[mesh.faces[seed][0]]);
  }
  // A facet's extent in a direction of its plane is reached on its border, so only the border's
  // vertices are kept: a finely meshed flat plate has a few thousand, not a million.
  facets.vertices.resize(facets.normal.size());
  for (const MeshEdge& edge : adjacency.edges) {
    const int a = facets.of_face[static_cast<std::size_t>(edge.f0)];
    const int b = edge.f1 >= 0 ? facets.of_face[static_cast<std::size_t>(edge.f1)] : -1;
    for (const int facet : {a, b}) {
      if (facet >= 0 && a != b) {
        facets.vertices[static_cast<std::size_t>(facet)].push_back(edge.v0);
        facets.vertices[static_cast<std::size_t>(facet)].push_back(edge.v1);
      }
    }
  }
  for (std::vector<int>& border : facets.vertices) {
    std::sort(border.begin(), border.end());
    border.erase(std::unique(border.begin(), border.end()), border.end());
  }
  return facets;
}

// The turn between two neighbouring facets, summed over the mesh edges they share.
struct FacetTurn {
  int a = -1;
  int b = -1;
  double length = 0.0;       // shared edge length [m]
  double turn_length = 0.0;  // Σ angle · length
  double convexity = 0.0;    // Σ sign · length: > 0 the surface bends away from its normal
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // Σ edge vectors, aligned
  Eigen::Vector3d point = Eigen::Vector3d::Zero();      // on the shared edge
  bool smooth_a = false;  // facet a reads it as a turn of the curve it is a facet of
  bool smooth_b = false;  // ... and facet b
};

// One side of a facet: where it turns, which way, by how much.
struct Side {
  Eigen::Vector3d outward;  // in the facet's plane, away from it
  double width = 0.0;       // facet's extent perpendicular to the shared edge [m]
  double angle = 0.0;       // [rad]
  int convex = 0;           // ±1
  bool comparable = false;  // the facet beyond is about as wide
  std::size_t turn = 0;     // index into the turn list
};

// Each facet's extent perpendicular to the shared edge, and the direction away from it.
bool sideOf(
    const Facets& facets, const Points& vertices, int facet, const FacetTurn& turn, Side* side) {
  const Eigen::Vector3d across =
      facets.normal[static_cast<std::size_t>(facet)].cross(turn.direction);
  if (!(across.norm() > 0.0)) {
    return false;
  }
  const Eigen::Vector3d d = across.normalized();
  double width = 0.0;
  for (const int v : facets.vertices[static_cast<std::size_t>(facet)]) {
    width = std::max(width, std::abs((vertices[static_cast<std::size_t>(v)] - turn.point).dot(d)));
  }
  const double inward = (facets.centroid[static_cast<std::size_t>(facet)] - turn.point).dot(d);
  side->outward = inward > 0.0 ? Eigen::Vector3d(-d) : d;
  side->width = width;
  return width > 0.0;
}

// The turns below a crease between facets, summed per pair of facets.
std::vector<FacetTurn> sumTurns(const TriangleMesh& mesh,
                                const Points& normals,
                                const MeshAdjacency& adjacency,
                                const Facets& facets) {
  std::vector<FacetTurn> turns;
  std::unordered_map<std::uint64_t, std::size_t> index;
  const auto centre = [&mesh](std::size_t face) {
    const Eigen::Vector3i& c = mesh.faces[face];
    return Eigen::Vector3d((mesh.vertices[static_cast<std::size_t>(c[0])] +
                            mesh.vertices[static_cast<std::size_t>(c[1])] +
                            mesh.vertices[static_cast<std::size_t>(c[2])]) /
                           3.0);
  };
  for (const MeshEdge& edge : adjacency.edges) {
    if (edge.f1 < 0) {
      continue;
    }
    const auto f = static_cast<std::size_t>(edge.f0);
    const auto g = static_cast<std::size_t>(edge.f1);
    const int a = facets.of_face[f];
    const int b = facets.of_face[g];
    if (a < 0 || b < 0 || a == b) {
      continue;
    }
    const double angle = std::acos(std::clamp(normals[f].dot(normals[g]), -1.0, 1.0));
    if (!(angle < kCreaseRad)) {
      continue;
    }
    const Eigen::Vector3d& p0 = mesh.vertices[static_cast<std::size_t>(edge.v0)];
    const Eigen::Vector3d along = mesh.vertices[static_cast<std::size_t>(edge.v1)] - p0;
    const double length = along.norm();
    const double bend = (normals[g] - normals[f]).dot(centre(g) - centre(f));
    const auto inserted = index.emplace(pairKey(a, b), turns.size());
    if (inserted.second) {
      FacetTurn turn;
      turn.a = std::min(a, b);
      turn.b = std::max(a, b);
      turn.point = p0;
      turns.push_back(turn);
    }
    FacetTurn& turn = turns[inserted.first->second];
    turn.length += length;
    turn.turn_length += angle * length;
    turn.convexity += (bend > 0.0 ? 1.0 : bend < 0.0 ? -1.0 : 0.0) * length;
    turn.direction += turn.direction.dot(along) < 0.0 ? Eigen::Vector3d(-along) : along;
  }
  return turns;
}

// Reads which turns are a curve's, per facet (FacetTurn::smooth_a/b), and returns each facet's
// chord error across its curve: a facet is one of a curve's when it turns the same way on two
// opposite sides and at least one of the two facets beyond is about as wide as it is (a flat
// face between two fillets' narrow facets is not). Across such a pair, a facet of width w
// between turns averaging θ stands for an arc of turn θ: its chord error is (w/2)·tan(θ/4),
// exact for a regular polygon.
std::vector<double> readCurves(const Facets& facets,
                               const Points& vertices,
                               std::vector<FacetTurn>* turns) {
  std::vector<std::vector<Side>> sides(facets.normal.size());
  for (std::size_t t = 0; t < turns->size(); ++t) {
    const FacetTurn& turn = (*turns)[t];
    Side a;
    Side b;
    if (!(turn.length > 0.0) || turn.convexity == 0.0 ||
        !sideOf(facets, vertices, turn.a, turn, &a) ||
        !sideOf(facets, vertices, turn.b, turn, &b)) {
      continue;
    }
    const bool comparable = std::max(a.width, b.width) <= kWidthRatio * std::min(a.width, b.width);
    for (Side* side : {&a, &b}) {
      side->angle = turn.turn_length / turn.length;
      side->convex = turn.convexity > 0.0 ? 1 : -1;
      side->comparable = comparable;
      side->turn = t;
    }
    sides[static_cast<std::size_t>(turn.a)].push_back(a);
    sides[static_cast<std::size_t>(turn.b)].push_back(b);
  }
  std::vector<double> error(facets.normal.size(), 0.0);
  for (std::size_t f = 0; f < sides.size(); ++f) {
    const std::vector<Side>& facet = sides[f];
    for (std::size_t i = 0; i < facet.size(); ++i) {
      for (std::size_t j = i + 1; j < facet.size(); ++j) {
        if (facet[i].convex != facet[j].convex || !(facet[i].comparable || facet[j].comparable) ||
            !(facet[i].outward.dot(facet[j].outward) < kOppositeCos)) {
          continue;
        }
        for (const Side* side : {&facet[i], &facet[j]}) {
          FacetTurn& turn = (*turns)[side->turn];
          (turn.a == static_cast<int>(f) ? turn.smooth_a : turn.smooth_b) = true;
        }
        const double width = 0.5 * (facet[i].width + facet[j].width);
        const double angle = 0.5 * (facet[i].angle + facet[j].angle);
        error[f] = std::max(error[f], 0.5 * width * std::tan(0.25 * angle));
      }
    }
  }
  return error;
}

// Angle of face `face` at its corner `corner`.
double cornerAngle(const TriangleMesh& mesh, std::size_t face, int corner) {
  const Eigen::Vector3i& c = mesh.faces[face];
  const Eigen::Vector3d& p = mesh.vertices[static_cast<std::size_t>(c[corner])];
  const Eigen::Vector3d e1 = mesh.vertices[static_cast<std::size_t>(c[(corner + 1) % 3])] - p;
  const Eigen::Vector3d e2 = mesh.vertices[static_cast<std::size_t>(c[(corner + 2) % 3])] - p;
  return std::atan2(e1.cross(e2).norm(), e1.dot(e2));
}

int cornerOf(const Eigen::Vector3i& face, int vertex) {
  return face[0] == vertex ? 0 : face[1] == vertex ? 1 : 2;
}

// Per face corner: the angle-weighted mean normal of the faces about the vertex that are joined
// to it through its own facet or smooth turns (a cylinder's ring vertex: both facets; a box's
// corner: the face alone).
std::vector<std::array<Eigen::Vector3d, 3>> cornerNormals(
    const TriangleMesh& mesh,
    const Points& normals,
    const MeshAdjacency& adjacency,
    const Facets& facets,
    const std::unordered_set<std::uint64_t>& smooth) {
  std::vector<std::array<Eigen::Vector3d, 3>> corner(
      mesh.faces.size(),
      {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
  std::vector<int> fan;
  std::vector<int> parent;
  std::vector<std::pair<int, int>> ends;
  for (std::size_t v = 0; v + 1 < adjacency.vertex_face_offsets.size(); ++v) {
    fan.clear();
    for (std::size_t k = adjacency.vertex_face_offsets[v]; k < adjacency.vertex_face_offsets[v + 1];
         ++k) {
      const int f = adjacency.vertex_faces[k];
      if (facets.of_face[static_cast<std::size_t>(f)] >= 0) {
        fan.push_back(f);
      }
    }
    parent.resize(fan.size());
    std::iota(parent.begin(), parent.end(), 0);
    const auto root = [&parent](int i) {
      while (parent[static_cast<std::size_t>(i)] != i) {
        i = parent[static_cast<std::size_t>(i)] =
            parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
      }
      return i;
    };
    const auto vertex = static_cast<int>(v);
    // Faces of the fan that share an edge from v share its other end: pairs (other end, face)
    // sorted, so a fan of any size is joined in k log k.
    ends.clear();
    for (std::size_t i = 0; i < fan.size(); ++i) {
      const Eigen::Vector3i& face = mesh.faces[static_cast<std::size_t>(fan[i])];
      for (int c = 0; c < 3; ++c) {
        if (face[c] != vertex) {
          ends.emplace_back(face[c], static_cast<int>(i));
        }
      }
    }
    std::sort(ends.begin(), ends.end());
    for (std::size_t k = 1; k < ends.size(); ++k) {
      if (ends[k].first != ends[k - 1].first) {
        continue;
      }
      const int i = ends[k - 1].second;
      const int j = ends[k].second;
      const int a = facets.of_face[static_cast<std::size_t>(fan[static_cast<std::size_t>(i)])];
      const int b = facets.of_face[static_cast<std::size_t>(fan[static_cast<std::size_t>(j)])];
      if (a == b || smooth.count(pairKey(a, b)) > 0) {
        parent[static_cast<std::size_t>(root(i))] = root(j);
      }
    }
    std::vector<Eigen::Vector3d> sum(fan.size(), Eigen::Vector3d::Zero());
    for (std::size_t i = 0; i < fan.size(); ++i) {
      const auto f = static_cast<std::size_t>(fan[i]);
      sum[static_cast<std::size_t>(root(static_cast<int>(i)))] +=
          cornerAngle(mesh, f, cornerOf(mesh.faces[f], vertex)) * normals[f];
    }
    for (std::size_t i = 0; i < fan.size(); ++i) {
      const auto f = static_cast<std::size_t>(fan[i]);
      const Eigen::Vector3d& s = sum[static_cast<std::size_t>(root(static_cast<int>(i)))];
      corner[f][static_cast<std::size_t>(cornerOf(mesh.faces[f], vertex))] =
          s.norm() > 0.0 ? Eigen::Vector3d(s.normalized()) : normals[f];
    }
  }
  return corner;
}

}  // namespace

ChordError estimateChordError(const TriangleMesh& mesh) {
  ChordError out;
  const std::size_t faces = mesh.faces.size();
  out.face.assign(faces, 0.0);
  out.bulge.assign(faces, {0.0, 0.0, 0.0});
  if (faces == 0) {
    return out;
  }
  const Points normals = mesh.face_normals.size() == faces
                             ? mesh.face_normals
                             : computeFaceNormals(mesh.vertices, mesh.faces);
  const MeshAdjacency adjacency = buildMeshAdjacency(mesh.faces, mesh.vertices.size());
  std::vector<std::array<int, 3>> face_edges(faces, {-1, -1, -1});
  for (std::size_t e = 0; e < adjacency.edges.size(); ++e) {
    for (const int f : {adjacency.edges[e].f0, adjacency.edges[e].f1}) {
      if (f < 0) {
        continue;
      }
      for (int& slot : face_edges[static_cast<std::size_t>(f)]) {
        if (slot < 0) {
          slot = static_cast<int>(e);
          break;
        }
      }
    }
  }
  const Facets facets = growFacets(mesh, normals, adjacency, face_edges);
  std::vector<FacetTurn> turns = sumTurns(mesh, normals, adjacency, facets);
  const std::vector<double> facet_error = readCurves(facets, mesh.vertices, &turns);
  // Vertex normals smooth across the turns both facets read as their curve's.
  std::unordered_set<std::uint64_t> smooth;
  for (const FacetTurn& turn : turns) {
    if (turn.smooth_a && turn.smooth_b) {
      smooth.insert(pairKey(turn.a, turn.b));
    }
  }
  const std::vector<std::array<Eigen::Vector3d, 3>> corner =
      cornerNormals(mesh, normals, adjacency, facets, smooth);
  // A face over a quadric, with the quadric's normals n_i at its corners x_i: linear
  // interpolation misses the surface by ½ Σ λ_i λ_j q_ij, q_ij = (n_j − n_i)·(x_j − x_i); at an
  // edge's middle q/8, at the centroid Σq/18.
  double area = 0.0;
  double curved_area = 0.0;
  for (std::size_t f = 0; f < faces; ++f) {
    const Eigen::Vector3i& c = mesh.faces[f];
    const double a = triangleArea(mesh.vertices, c);
    area += a;
    if (facets.of_face[f] < 0) {
      continue;
    }
    const double across = facet_error[static_cast<std::size_t>(facets.of_face[f])];
    if (across > 0.0) {
      curved_area += a;
    }
    double largest = 0.0;
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      const double q =
          (corner[f][static_cast<std::size_t>(j)] - corner[f][static_cast<std::size_t>(i)])
              .dot(mesh.vertices[static_cast<std::size_t>(c[j])] -
                   mesh.vertices[static_cast<std::size_t>(c[i])]);
      out.bulge[f][static_cast<std::size_t>(i)] = q;
      largest = std::max(largest, std::abs(q));
      sum += q;
    }
    out.face[f] = std::max({across, largest / 8.0, std::abs(sum) / 18.0});
    if (out.face[f] > out.max) {
      out.max = out.face[f];
      out.max_at = (mesh.vertices[static_cast<std::size_t>(c[0])] +
                    mesh.vertices[static_cast<std::size_t>(c[1])] +
                    mesh.vertices[static_cast<std::size_t>(c[2])]) /
                   3.0;
    }
  }
  out.curved_area_share = area > 0.0 ? curved_area / area : 0.0;
  return out;
}

double bulgeAt(const ChordError& error,
               const TriangleMesh& mesh,
               int face,
               const Eigen::Vector3d& point) {
  if (face < 0 || static_cast<std::size_t>(face) >= error.bulge.size() ||
      static_cast<std::size_t>(face) >= mesh.faces.size()) {
    return 0.0;
  }
  const std::array<double, 3>& q = error.bulge[static_cast<std::size_t>(face)];
  if (q[0] == 0.0 && q[1] == 0.0 && q[2] == 0.0) {
    return 0.0;
  }
  const Eigen::Vector3i& c = mesh.faces[static_cast<std::size_t>(face)];
  const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(c[0])];
  const Eigen::Vector3d ab = mesh.vertices[static_cast<std::size_t>(c[1])] - a;
  const Eigen::Vector3d ac = mesh.vertices[static_cast<std::size_t>(c[2])] - a;
  const Eigen::Vector3d ap = point - a;
  const double d00 = ab.dot(ab);
  const double d01 = ab.dot(ac);
  const double d11 = ac.dot(ac);
  const double denominator = d00 * d11 - d01 * d01;
  if (!(denominator > 0.0)) {
    return 0.0;
  }
  const double l1 = std::clamp((d11 * ab.dot(ap) - d01 * ac.dot(ap)) / denominator, 0.0, 1.0);
  const double l2 = std::clamp((d00 * ac.dot(ap) - d01 * ab.dot(ap)) / denominator, 0.0, 1.0);
  const double l0 = std::max(0.0, 1.0 - l1 - l2);
  return 0.5 * (l0 * l1 * q[0] + l1 * l2 * q[1] + l2 * l0 * q[2]);
}

}  // namespace freeform_inspection
