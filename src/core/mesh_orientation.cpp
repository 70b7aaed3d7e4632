// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/mesh_orientation.h"

#include <algorithm>
#include <unordered_map>

#include <Eigen/Geometry>

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

// One use of an undirected edge: the face and the corner the edge starts at.
struct EdgeUse {
  int face = -1;
  int corner = -1;
  bool forward = false;  // traversed from the lower to the higher vertex index
};

std::uint64_t undirectedKey(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b)));
  const auto hi = static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::max(a, b)));
  return (lo << 32U) | hi;
}

std::unordered_map<std::uint64_t, std::vector<EdgeUse>> edgeUses(const Triangles& faces) {
  std::unordered_map<std::uint64_t, std::vector<EdgeUse>> uses;
  uses.reserve(faces.size() * 2);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int from = faces[f][c];
      const int to = faces[f][(c + 1) % 3];
      uses[undirectedKey(from, to)].push_back({static_cast<int>(f), c, from < to});
    }
  }
  return uses;
}

}  // namespace

OrientationResult orientOutward(TriangleMesh* mesh) {
  OrientationResult result;
  Triangles& faces = mesh->faces;
  const auto uses = edgeUses(faces);
  // Face graph over manifold edges; `same` marks neighbours whose winding disagrees (both
  // traverse the shared edge the same way), so one of them must flip relative to the other.
  struct Link {
    int face;
    bool disagree;
  };
  std::vector<std::vector<Link>> links(faces.size());
  for (const auto& entry : uses) {
    const auto& list = entry.second;
    if (list.size() != 2 || list[0].face == list[1].face) {
      continue;  // border or non-manifold: no orientation constraint across it
    }
    const bool disagree = list[0].forward == list[1].forward;
    links[static_cast<std::size_t>(list[0].face)].push_back({list[1].face, disagree});
    links[static_cast<std::size_t>(list[1].face)].push_back({list[0].face, disagree});
  }
  std::vector<int> component(faces.size(), -1);
  std::vector<bool> flip(faces.size(), false);
  std::vector<int> stack;
  for (std::size_t seed = 0; seed < faces.size(); ++seed) {
    if (component[seed] >= 0) {
      continue;
    }
    const int id = static_cast<int>(result.components++);
    std::vector<int> members;
    component[seed] = id;
    stack.push_back(static_cast<int>(seed));
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      members.push_back(f);
      for (const Link& link : links[static_cast<std::size_t>(f)]) {
        const auto g = static_cast<std::size_t>(link.face);
        if (component[g] < 0) {
          component[g] = id;
          flip[g] = flip[static_cast<std::size_t>(f)] != link.disagree;
          stack.push_back(link.face);
        }
      }
    }
    // Closed pieces: the enclosed volume must be positive. Open pieces: keep the winding most
    // of the area already had.
    bool closed = true;
    double volume = 0.0;
    double area_kept = 0.0;
    double area_flipped = 0.0;
    for (const int f : members) {
      const Eigen::Vector3i& face = faces[static_cast<std::size_t>(f)];
      for (int c = 0; c < 3 && closed; ++c) {
        closed = uses.at(undirectedKey(face[c], face[(c + 1) % 3])).size() == 2;
      }
      const double sign = flip[static_cast<std::size_t>(f)] ? -1.0 : 1.0;
      const Eigen::Vector3d& a = mesh->vertices[static_cast<std::size_t>(face[0])];
      const Eigen::Vector3d& b = mesh->vertices[static_cast<std::size_t>(face[1])];
      const Eigen::Vector3d& c = mesh->vertices[static_cast<std::size_t>(face[2])];
      volume += sign * a.dot(b.cross(c)) / 6.0;
      (flip[static_cast<std::size_t>(f)] ? area_flipped : area_kept) +=
          triangleArea(mesh->vertices, face);
    }
    const bool reverse = closed ? volume < 0.0 : area_flipped > area_kept;
    if (reverse) {
      ++result.reversed_components;
      for (const int f : members) {
        flip[static_cast<std::size_t>(f)] = !flip[static_cast<std::size_t>(f)];
      }
    }
  }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (flip[f]) {
      std::swap(faces[f][1], faces[f][2]);
      ++result.flipped_faces;
    }
  }
  if (result.flipped_faces > 0 || mesh->face_normals.size() != faces.size()) {
    mesh->face_normals = computeFaceNormals(mesh->vertices, faces);
  }
  return result;
}

std::vector<std::uint8_t> borderEdgeMasks(const TriangleMesh& mesh) {
  const auto uses = edgeUses(mesh.faces);
  std::vector<std::uint8_t> masks;
  for (const auto& entry : uses) {
    if (entry.second.size() != 1) {
      continue;
    }
    if (masks.empty()) {
      masks.assign(mesh.faces.size(), 0);
    }
    const EdgeUse& use = entry.second.front();
    masks[static_cast<std::size_t>(use.face)] |= static_cast<std::uint8_t>(1U << use.corner);
  }
  return masks;
}

}  // namespace freeform_inspection
