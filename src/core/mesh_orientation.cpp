// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/mesh_orientation.h"

#include <algorithm>
#include <cstdint>

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

// Every face corner's edge, grouped by undirected edge: uses[offsets[e] .. offsets[e+1]) share
// edge e, in face order. Built by bucketing on the lower vertex, then a stable sort on the
// higher one inside each (small) bucket: linear time and one allocation per array, where a hash
// map of vectors spent most of a CAD load in malloc.
struct EdgeUseTable {
  std::vector<EdgeUse> uses;
  std::vector<std::size_t> offsets;       // size edges + 1
  std::vector<std::uint32_t> group_size;  // per face corner (3 f + c): faces using its edge

  std::size_t edges() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::size_t size(std::size_t edge) const { return offsets[edge + 1] - offsets[edge]; }
  const EdgeUse& use(std::size_t edge, std::size_t i) const { return uses[offsets[edge] + i]; }
};

EdgeUseTable edgeUses(const Triangles& faces) {
  int vertex_count = 0;
  for (const auto& f : faces) {
    vertex_count = std::max(vertex_count, f.maxCoeff() + 1);
  }
  std::vector<std::size_t> bucket_start(static_cast<std::size_t>(vertex_count) + 1, 0);
  for (const auto& f : faces) {
    for (int c = 0; c < 3; ++c) {
      ++bucket_start[static_cast<std::size_t>(std::min(f[c], f[(c + 1) % 3])) + 1];
    }
  }
  for (std::size_t v = 1; v < bucket_start.size(); ++v) {
    bucket_start[v] += bucket_start[v - 1];
  }
  struct Entry {
    int higher;
    EdgeUse use;
  };
  std::vector<Entry> entries(3 * faces.size());
  std::vector<std::size_t> fill(bucket_start.begin(), bucket_start.end() - 1);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int from = faces[f][c];
      const int to = faces[f][(c + 1) % 3];
      entries[fill[static_cast<std::size_t>(std::min(from, to))]++] = {
          std::max(from, to), {static_cast<int>(f), c, from < to}};
    }
  }
  EdgeUseTable table;
  table.uses.reserve(entries.size());
  table.offsets.reserve(entries.size() / 2 + 1);
  table.group_size.assign(entries.size(), 0);
  for (std::size_t v = 0; v + 1 < bucket_start.size(); ++v) {
    const auto first = entries.begin() + static_cast<std::ptrdiff_t>(bucket_start[v]);
    const auto last = entries.begin() + static_cast<std::ptrdiff_t>(bucket_start[v + 1]);
    std::stable_sort(
        first, last, [](const Entry& a, const Entry& b) { return a.higher < b.higher; });
    for (auto it = first; it != last; ++it) {
      if (it == first || it->higher != (it - 1)->higher) {
        table.offsets.push_back(table.uses.size());
      }
      table.uses.push_back(it->use);
    }
  }
  table.offsets.push_back(table.uses.size());
  for (std::size_t e = 0; e < table.edges(); ++e) {
    for (std::size_t i = 0; i < table.size(e); ++i) {
      const EdgeUse& u = table.use(e, i);
      table.group_size[3 * static_cast<std::size_t>(u.face) + static_cast<std::size_t>(u.corner)] =
          static_cast<std::uint32_t>(table.size(e));
    }
  }
  return table;
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
  for (std::size_t e = 0; e < uses.edges(); ++e) {
    if (uses.size(e) != 2 || uses.use(e, 0).face == uses.use(e, 1).face) {
      continue;  // border or non-manifold: no orientation constraint across it
    }
    const EdgeUse& first = uses.use(e, 0);
    const EdgeUse& second = uses.use(e, 1);
    const bool disagree = first.forward == second.forward;
    links[static_cast<std::size_t>(first.face)].push_back({second.face, disagree});
    links[static_cast<std::size_t>(second.face)].push_back({first.face, disagree});
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
      for (std::size_t c = 0; c < 3 && closed; ++c) {
        closed = uses.group_size[3 * static_cast<std::size_t>(f) + c] == 2;
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
  for (std::size_t e = 0; e < uses.edges(); ++e) {
    if (uses.size(e) != 1) {
      continue;
    }
    if (masks.empty()) {
      masks.assign(mesh.faces.size(), 0);
    }
    const EdgeUse& use = uses.use(e, 0);
    masks[static_cast<std::size_t>(use.face)] |= static_cast<std::uint8_t>(1U << use.corner);
  }
  return masks;
}

}  // namespace freeform_inspection
