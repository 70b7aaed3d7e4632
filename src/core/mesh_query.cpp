// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/mesh_query.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <string>
#include <utility>

#include <Eigen/Geometry>
#include <embree3/rtcore.h>

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

// Which part of a triangle holds the closest point: its interior, one of its edges
// (0: v0–v1, 1: v1–v2, 2: v2–v0) or one of its corners (0, 1, 2).
enum class Feature { kFace, kEdge, kVertex };

struct TrianglePoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double squared_distance = std::numeric_limits<double>::infinity();
  Feature feature = Feature::kFace;
  int index = 0;  ///< edge or corner number within the triangle
};

// Closest point of the segment a–b (corners `ia`, `ib`, edge `edge`) to p.
TrianglePoint closestOnSegment(const Eigen::Vector3d& p,
                               const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b,
                               int ia,
                               int ib,
                               int edge) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  TrianglePoint result;
  if (t <= 0.0) {
    result.point = a;
    result.feature = Feature::kVertex;
    result.index = ia;
  } else if (t >= 1.0) {
    result.point = b;
    result.feature = Feature::kVertex;
    result.index = ib;
  } else {
    result.point = a + t * ab;
    result.feature = Feature::kEdge;
    result.index = edge;
  }
  result.squared_distance = (p - result.point).squaredNorm();
  return result;
}

// Below this sin² of the angle at v0 the face is treated as its three edges: the barycentric
// denominator |ab × ac|² is then dominated by cancellation (and is zero for degenerate faces).
constexpr double kSliverSin2 = 1e-14;

// Whether the face with edges ab and ac from its first corner is that thin.
bool isSliver(const Eigen::Vector3d& ab, const Eigen::Vector3d& ac) {
  return !(ab.cross(ac).squaredNorm() > kSliverSin2 * ab.squaredNorm() * ac.squaredNorm());
}

/// Closest point on triangle (a, b, c) to p, by the Voronoi region of p (Ericson, Real-Time
/// Collision Detection, 5.1.5), in double. `sliver`: isSliver(b − a, c − a), which the face
/// table keeps so that no query computes it again.
TrianglePoint closestOnTriangle(const Eigen::Vector3d& p,
                                const Eigen::Vector3d& a,
                                const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c,
                                bool sliver) {
  if (sliver) {
    TrianglePoint best = closestOnSegment(p, a, b, 0, 1, 0);
    for (const TrianglePoint& other :
         {closestOnSegment(p, b, c, 1, 2, 1), closestOnSegment(p, c, a, 2, 0, 2)}) {
      if (other.squared_distance < best.squared_distance) {
        best = other;
      }
    }
    return best;
  }
  const auto finish = [&p](const Eigen::Vector3d& point, Feature feature, int index) {
    TrianglePoint result;
    result.point = point;
    result.feature = feature;
    result.index = index;
    result.squared_distance = (p - point).squaredNorm();
    return result;
  };
  const Eigen::Vector3d ab = b - a;
  const Eigen::Vector3d ac = c - a;
  const Eigen::Vector3d ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    return finish(a, Feature::kVertex, 0);
  }
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) {
    return finish(b, Feature::kVertex, 1);
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    return finish(a + (d1 / (d1 - d3)) * ab, Feature::kEdge, 0);
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) {
    return finish(c, Feature::kVertex, 2);
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    return finish(a + (d2 / (d2 - d6)) * ac, Feature::kEdge, 2);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return finish(b + w * (c - b), Feature::kEdge, 1);
  }
  const double denominator = 1.0 / (va + vb + vc);
  return finish(a + ab * (vb * denominator) + ac * (vc * denominator), Feature::kFace, 0);
}

// Double → float for Embree without the undefined behaviour of out-of-range conversions.
bool representable(const Eigen::Vector3d& v) {
  return v.allFinite() && v.cwiseAbs().maxCoeff() < 1e30;
}

// Rounds a non-negative distance up to a float (infinity when it does not fit).
float floatAtLeast(double value) {
  if (!(value < static_cast<double>(FLT_MAX))) {
    return std::numeric_limits<float>::infinity();
  }
  float f = static_cast<float>(value);
  if (static_cast<double>(f) < value) {
    f = std::nextafter(f, std::numeric_limits<float>::infinity());
  }
  return f;
}

const char* embreeErrorName(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "none";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
    default:
      return "unknown error";
  }
}

// One id per undirected edge, for the edges v0v1, v1v2, v2v0 of each face. The half-edges are
// bucketed by their lower vertex and sorted by the higher one within it: linear in the faces
// but for the sorts of the small buckets (a hash map of edge keys took 10 ms of each 58k-face
// model load).
std::vector<std::array<int, 3>> undirectedEdgeIds(const Triangles& faces,
                                                  std::size_t vertex_count,
                                                  int* edge_count) {
  std::vector<std::size_t> start(vertex_count + 1, 0);
  for (const Eigen::Vector3i& f : faces) {
    for (int c = 0; c < 3; ++c) {
      ++start[static_cast<std::size_t>(std::min(f[c], f[(c + 1) % 3])) + 1];
    }
  }
  for (std::size_t v = 0; v < vertex_count; ++v) {
    start[v + 1] += start[v];
  }
  // (higher vertex, half-edge 3 * face + corner) in each lower vertex's bucket.
  std::vector<std::pair<int, std::size_t>> bucketed(3 * faces.size());
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const Eigen::Vector3i& f = faces[i];
    for (int c = 0; c < 3; ++c) {
      const int a = f[c];
      const int b = f[(c + 1) % 3];
      bucketed[next[static_cast<std::size_t>(std::min(a, b))]++] = {
          std::max(a, b), 3 * i + static_cast<std::size_t>(c)};
    }
  }
  std::vector<std::array<int, 3>> ids(faces.size());
  int edges = 0;
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const auto first = bucketed.begin() + static_cast<long>(start[v]);
    const auto last = bucketed.begin() + static_cast<long>(start[v + 1]);
    std::sort(first, last);
    for (auto it = first; it != last; ++it) {
      if (it != first && it->first != (it - 1)->first) {
        ++edges;
      }
      ids[it->second / 3][it->second % 3] = edges;
    }
    edges += first != last ? 1 : 0;
  }
  *edge_count = edges;
  return ids;
}

}  // namespace

// Named (not anonymous) so that MeshQuery::Impl may derive from it; the Embree callbacks below
// see this part, since MeshQuery::Impl itself is private.
namespace mesh_query_internal {

struct Data {
  TriangleMesh mesh;
  Status status;
  // Pseudo-normals (Bærentzen & Aanæs 2005), not normalized: only their direction matters.
  std::vector<std::array<int, 3>> face_edges;  ///< edge ids of edges v0v1, v1v2, v2v0
  Points edge_normals;                         ///< sum of the adjacent unit face normals
  Points vertex_normals;                       ///< angle-weighted sum of incident face normals
  // Each face's corners side by side with its plane, so a query reads one face from one place
  // instead of three vertices from wherever the mesh keeps them.
  struct FaceGeometry {
    std::array<Eigen::Vector3d, 3> corners;
    Eigen::Vector3d plane_normal;  ///< unit; zero for a sliver, whose plane bounds nothing
    bool sliver;                   ///< isSliver() of its edges from corner 0
  };
  std::vector<FaceGeometry> face_geometry;
  // Embree works in float; coordinates are shifted to the box centre to keep float precision
  // relative to the part, not to its distance from the origin.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double half_extent = 0.0;  ///< [m] largest |v − centre| coordinate
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::mutex error_mutex;
  std::string embree_error;

  ~Data() {
    if (scene != nullptr) {
      rtcReleaseScene(scene);
    }
    if (device != nullptr) {
      rtcReleaseDevice(device);
    }
  }

  bool valid() const { return status.ok() && scene != nullptr; }

  const Eigen::Vector3d& vertex(int face, int corner) const {
    return mesh
        .vertices[static_cast<std::size_t>(mesh.faces[static_cast<std::size_t>(face)][corner])];
  }

  Status validate() const;
  void computeFaceGeometry();
  void computePseudoNormals();
  Status buildScene();
  Eigen::Vector3d pseudoNormal(int face, const TrianglePoint& closest) const;

  // Embree culls with float boxes of float vertices around a float query point: the radius
  // is padded by their rounding error so that no triangle within the exact double distance is
  // skipped.
  float searchRadius(double distance, const Eigen::Vector3d& local_query) const {
    const double margin =
        8.0 * static_cast<double>(FLT_EPSILON) * (half_extent + local_query.cwiseAbs().maxCoeff());
    return floatAtLeast(distance * (1.0 + 8.0 * static_cast<double>(FLT_EPSILON)) + margin);
  }
};

}  // namespace mesh_query_internal

struct MeshQuery::Impl : mesh_query_internal::Data {};

namespace {

using mesh_query_internal::Data;

// Per-query state handed to the Embree callback.
struct PointQueryState {
  const Data* impl = nullptr;
  Eigen::Vector3d query = Eigen::Vector3d::Zero();        // mesh frame
  Eigen::Vector3d local_query = Eigen::Vector3d::Zero();  // centred frame, as Embree sees it
  double max_distance = 0.0;
  // closestFacing(): only faces whose normal agrees with this one (zero: every face).
  Eigen::Vector3d facing = Eigen::Vector3d::Zero();
  double min_cos = -1.0;
  bool oriented = true;
  int face = -1;
  TrianglePoint best;
};

bool facesTheWay(const PointQueryState& state, int face) {
  if (state.facing.isZero()) {
    return true;
  }
  const double agreement =
      state.facing.dot(state.impl->mesh.face_normals[static_cast<std::size_t>(face)]);
  return (state.oriented ? agreement : std::abs(agreement)) >= state.min_cos;
}

// Whether the face's plane alone is farther than the best so far (or the distance bound): no
// point of the face can then win. The margin covers the rounding of the plane's normal and of
// both distances (relative 1e-9 for faces that are not slivers), so only faces that could not
// win are skipped and the answer stays the exact search's.
bool planeBeyondReach(const PointQueryState& state, const Data::FaceGeometry& face) {
  const Eigen::Vector3d offset = state.query - face.corners[0];
  const double margin = 1e-7 * offset.cwiseAbs().sum();
  const double lower = std::abs(face.plane_normal.dot(offset)) - margin;
  if (!(lower > 0.0)) {
    return false;
  }
  return lower > state.max_distance ||
         (state.face >= 0 && lower * lower > state.best.squared_distance);
}

// Offers one face; true when it became the best so far. Equal distances go to the lower face
// index, so the answer does not depend on the traversal order.
bool considerFace(PointQueryState& state, int face) {
  if (!facesTheWay(state, face)) {
    return false;
  }
  const Data::FaceGeometry& geometry = state.impl->face_geometry[static_cast<std::size_t>(face)];
  if (planeBeyondReach(state, geometry)) {
    return false;
  }
  const TrianglePoint candidate = closestOnTriangle(
      state.query, geometry.corners[0], geometry.corners[1], geometry.corners[2], geometry.sliver);
  if (!std::isfinite(candidate.squared_distance) ||
      !(std::sqrt(candidate.squared_distance) <= state.max_distance)) {
    return false;
  }
  if (state.face >= 0 &&
      !(candidate.squared_distance < state.best.squared_distance ||
        (candidate.squared_distance == state.best.squared_distance && face < state.face))) {
    return false;
  }
  state.face = face;
  state.best = candidate;
  return true;
}

bool pointQueryCallback(RTCPointQueryFunctionArguments* args) {
  auto* state = static_cast<PointQueryState*>(args->userPtr);
  if (!considerFace(*state, static_cast<int>(args->primID))) {
    return false;
  }
  const float radius =
      state->impl->searchRadius(std::sqrt(state->best.squared_distance), state->local_query);
  if (radius < args->query->radius) {
    args->query->radius = radius;
    return true;  // tells Embree the search sphere shrank
  }
  return false;
}

void embreeErrorCallback(void* user, RTCError code, const char* text) {
  auto* impl = static_cast<Data*>(user);
  const std::lock_guard<std::mutex> lock(impl->error_mutex);
  if (impl->embree_error.empty()) {
    impl->embree_error = std::string(embreeErrorName(code)) + ": " + (text ? text : "");
  }
}

}  // namespace

Status mesh_query_internal::Data::validate() const {
  if (mesh.faces.empty()) {
    return Status::failure(StatusCode::kInvalidInput, "mesh query: the mesh has no faces");
  }
  if (mesh.vertices.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
      mesh.faces.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    return Status::failure(StatusCode::kInvalidInput, "mesh query: too many vertices or faces");
  }
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!representable(mesh.vertices[i])) {
      return Status::failure(
          StatusCode::kInvalidInput,
          "mesh query: vertex " + std::to_string(i) + " is non-finite or beyond 1e30 m");
    }
  }
  const auto vertex_count = static_cast<long long>(mesh.vertices.size());
  double area = 0.0;
  for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
    const Eigen::Vector3i& f = mesh.faces[i];
    for (int c = 0; c < 3; ++c) {
      if (f[c] < 0 || f[c] >= vertex_count) {
        return Status::failure(StatusCode::kInvalidInput,
                               "mesh query: face " + std::to_string(i) + " uses vertex " +
                                   std::to_string(f[c]) + " of " + std::to_string(vertex_count));
      }
    }
    area += triangleArea(mesh.vertices, f);
  }
  if (!(area > 0.0)) {
    return Status::failure(
        StatusCode::kDegenerateInput,
        "mesh query: all " + std::to_string(mesh.faces.size()) + " faces have zero area");
  }
  return Status::success();
}

void mesh_query_internal::Data::computeFaceGeometry() {
  face_geometry.resize(mesh.faces.size());
  for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
    FaceGeometry& face = face_geometry[i];
    for (int c = 0; c < 3; ++c) {
      face.corners[static_cast<std::size_t>(c)] = vertex(static_cast<int>(i), c);
    }
    // Where closestOnTriangle() treats a face as its edges, the computed normal may point
    // anywhere.
    face.sliver = isSliver(face.corners[1] - face.corners[0], face.corners[2] - face.corners[0]);
    face.plane_normal = face.sliver ? Eigen::Vector3d::Zero() : mesh.face_normals[i];
  }
}

void mesh_query_internal::Data::computePseudoNormals() {
  int edge_count = 0;
  face_edges = undirectedEdgeIds(mesh.faces, mesh.vertices.size(), &edge_count);
  edge_normals.assign(static_cast<std::size_t>(edge_count), Eigen::Vector3d::Zero());
  vertex_normals.assign(mesh.vertices.size(), Eigen::Vector3d::Zero());
  // In face order, as each sum always was: the same normals bit for bit.
  for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
    const Eigen::Vector3i& f = mesh.faces[i];
    const Eigen::Vector3d& n = mesh.face_normals[i];
    for (int c = 0; c < 3; ++c) {
      edge_normals[static_cast<std::size_t>(face_edges[i][static_cast<std::size_t>(c)])] += n;
      // Angle of this face at corner c.
      const Eigen::Vector3d& p = vertex(static_cast<int>(i), c);
      const Eigen::Vector3d e1 = vertex(static_cast<int>(i), (c + 1) % 3) - p;
      const Eigen::Vector3d e2 = vertex(static_cast<int>(i), (c + 2) % 3) - p;
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      vertex_normals[static_cast<std::size_t>(f[c])] += angle * n;
    }
  }
}

Status mesh_query_internal::Data::buildScene() {
  device = rtcNewDevice(nullptr);
  if (device == nullptr) {
    return Status::failure(StatusCode::kInvalidInput,
                           std::string("mesh query: Embree device creation failed: ") +
                               embreeErrorName(rtcGetDeviceError(nullptr)));
  }
  rtcSetDeviceErrorFunction(device, embreeErrorCallback, this);
  scene = rtcNewScene(device);
  if (scene != nullptr) {
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (geometry != nullptr) {
      rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
      auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry,
                                                                   RTC_BUFFER_TYPE_VERTEX,
                                                                   0,
                                                                   RTC_FORMAT_FLOAT3,
                                                                   3 * sizeof(float),
                                                                   mesh.vertices.size()));
      auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry,
                                                                     RTC_BUFFER_TYPE_INDEX,
                                                                     0,
                                                                     RTC_FORMAT_UINT3,
                                                                     3 * sizeof(unsigned),
                                                                     mesh.faces.size()));
      if (vertices != nullptr && indices != nullptr) {
        for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
          const Eigen::Vector3d local = mesh.vertices[i] - centre;
          for (int k = 0; k < 3; ++k) {
            vertices[3 * i + static_cast<std::size_t>(k)] = static_cast<float>(local[k]);
          }
        }
        for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
          for (int k = 0; k < 3; ++k) {
            indices[3 * i + static_cast<std::size_t>(k)] = static_cast<unsigned>(mesh.faces[i][k]);
          }
        }
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene, geometry);
      }
      rtcReleaseGeometry(geometry);
      rtcCommitScene(scene);
    }
  }
  const RTCError error = rtcGetDeviceError(device);
  const std::lock_guard<std::mutex> lock(error_mutex);
  if (scene == nullptr || error != RTC_ERROR_NONE || !embree_error.empty()) {
    const std::string text = embree_error.empty() ? embreeErrorName(error) : embree_error;
    if (scene != nullptr) {
      rtcReleaseScene(scene);
      scene = nullptr;
    }
    return Status::failure(StatusCode::kInvalidInput, "mesh query: Embree failed: " + text);
  }
  return Status::success();
}

Eigen::Vector3d mesh_query_internal::Data::pseudoNormal(int face,
                                                        const TrianglePoint& closest) const {
  const auto f = static_cast<std::size_t>(face);
  switch (closest.feature) {
    case Feature::kEdge:
      return edge_normals[static_cast<std::size_t>(
          face_edges[f][static_cast<std::size_t>(closest.index)])];
    case Feature::kVertex:
      return vertex_normals[static_cast<std::size_t>(mesh.faces[f][closest.index])];
    case Feature::kFace:
    default:
      return mesh.face_normals[f];
  }
}

MeshQuery::MeshQuery(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->mesh = mesh;
  impl_->status = impl_->validate();
  if (!impl_->status.ok()) {
    return;
  }
  impl_->mesh.face_normals = computeFaceNormals(impl_->mesh.vertices, impl_->mesh.faces);
  const BoundingBox box = computeBoundingBox(impl_->mesh.vertices);
  impl_->centre = 0.5 * (box.min + box.max);
  impl_->half_extent = 0.5 * box.extent().maxCoeff();
  impl_->computeFaceGeometry();
  impl_->computePseudoNormals();
  impl_->status = impl_->buildScene();
}

MeshQuery::~MeshQuery() = default;

const Status& MeshQuery::status() const {
  return impl_->status;
}

const TriangleMesh& MeshQuery::mesh() const {
  return impl_->mesh;
}

namespace {

// The search behind closest() and closestFacing(): `state` holds the distance bound and filter.
// A `hint` face within reach is offered first and its distance bounds the search: the answer
// is the same, the least (distance, face) over every face the search radius admits.
ClosestPoint closestOnMesh(const Data& data,
                           const Eigen::Vector3d& query,
                           PointQueryState& state,
                           int hint = -1) {
  ClosestPoint result;
  if (!data.valid() || !query.allFinite() || std::isnan(state.max_distance) ||
      state.max_distance < 0.0) {
    return result;
  }
  state.impl = &data;
  state.query = query;
  state.local_query = query - data.centre;
  double max_distance = state.max_distance;
  if (hint >= 0 && static_cast<std::size_t>(hint) < data.mesh.faces.size() &&
      considerFace(state, hint)) {
    max_distance = std::min(max_distance, std::sqrt(state.best.squared_distance));
  }
  if (representable(state.local_query)) {
    RTCPointQuery point_query;
    point_query.x = static_cast<float>(state.local_query.x());
    point_query.y = static_cast<float>(state.local_query.y());
    point_query.z = static_cast<float>(state.local_query.z());
    point_query.time = 0.0f;
    point_query.radius = data.searchRadius(max_distance, state.local_query);
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(data.scene, &point_query, &context, pointQueryCallback, &state);
  } else {
    // Too far away for Embree's float coordinates: every face is a candidate anyway.
    for (std::size_t f = 0; f < data.mesh.faces.size(); ++f) {
      considerFace(state, static_cast<int>(f));
    }
  }
  if (state.face < 0) {
    return result;
  }
  result.found = true;
  result.face = state.face;
  result.point = state.best.point;
  result.normal = data.mesh.face_normals[static_cast<std::size_t>(state.face)];
  result.distance = std::sqrt(state.best.squared_distance);
  if (result.distance == 0.0) {
    result.signed_distance = 0.0;
  } else {
    // Ties (query in the plane of the pseudo-normal, e.g. beside an open boundary) count as
    // outside.
    const double side = (query - result.point).dot(data.pseudoNormal(state.face, state.best));
    result.signed_distance = side < 0.0 ? -result.distance : result.distance;
  }
  return result;
}

}  // namespace

ClosestPoint MeshQuery::closest(const Eigen::Vector3d& query, double max_distance) const {
  PointQueryState state;
  state.max_distance = max_distance;
  return closestOnMesh(*impl_, query, state);
}

namespace {

// The search state of closestFacing(): faces turned like `normal` only (every face for a zero
// or non-finite normal).
PointQueryState facingState(const Eigen::Vector3d& normal,
                            double min_cos,
                            bool oriented,
                            double max_distance) {
  PointQueryState state;
  state.max_distance = max_distance;
  if (normal.allFinite() && normal.norm() > 0.0) {
    state.facing = normal.normalized();
    state.min_cos = min_cos;
    state.oriented = oriented;
  }
  return state;
}

}  // namespace

ClosestPoint MeshQuery::closestFacing(const Eigen::Vector3d& query,
                                      const Eigen::Vector3d& normal,
                                      double min_cos,
                                      bool oriented,
                                      double max_distance) const {
  PointQueryState state = facingState(normal, min_cos, oriented, max_distance);
  return closestOnMesh(*impl_, query, state);
}

std::vector<ClosestPoint> MeshQuery::closestFacing(const Points& queries,
                                                   const Points& normals,
                                                   double min_cos,
                                                   bool oriented,
                                                   double max_distance,
                                                   const std::vector<int>& hints) const {
  std::vector<ClosestPoint> results(queries.size());
  const auto count = static_cast<long long>(queries.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (long long i = 0; i < count; ++i) {
    const auto u = static_cast<std::size_t>(i);
    PointQueryState state = facingState(
        u < normals.size() ? normals[u] : Eigen::Vector3d::Zero(), min_cos, oriented, max_distance);
    results[u] = closestOnMesh(*impl_, queries[u], state, u < hints.size() ? hints[u] : -1);
  }
  return results;
}

std::vector<ClosestPoint> MeshQuery::closest(const Points& queries, double max_distance) const {
  return closest(queries, max_distance, std::vector<int>());
}

std::vector<ClosestPoint> MeshQuery::closest(const Points& queries,
                                             double max_distance,
                                             const std::vector<int>& hints) const {
  // No normals: every face counts, the plain closest point.
  return closestFacing(queries, Points(), -1.0, true, max_distance, hints);
}

RayHit MeshQuery::castRay(const Eigen::Vector3d& origin,
                          const Eigen::Vector3d& direction,
                          double t_min,
                          double t_max) const {
  RayHit result;
  const double length = direction.norm();
  if (!impl_->valid() || !origin.allFinite() || !std::isfinite(length) || !(length > 0.0) ||
      !std::isfinite(t_min) || std::isnan(t_max) || !(t_max > t_min)) {
    return result;
  }
  const Eigen::Vector3d unit = direction / length;
  // Embree wants tnear >= 0: start the ray at t_min instead and add it back.
  const Eigen::Vector3d start = origin + t_min * unit;
  const Eigen::Vector3d local = start - impl_->centre;
  if (!representable(local)) {
    return result;
  }
  const double span = t_max - t_min;  // > 0, maybe infinite
  float t_near = 0.0f;
  // A hit Embree finds at t ≈ 0 in float may lie at or before t_min in double: then look on.
  for (int attempt = 0; attempt < 8; ++attempt) {
    RTCRayHit ray_hit;
    ray_hit.ray.org_x = static_cast<float>(local.x());
    ray_hit.ray.org_y = static_cast<float>(local.y());
    ray_hit.ray.org_z = static_cast<float>(local.z());
    ray_hit.ray.dir_x = static_cast<float>(unit.x());
    ray_hit.ray.dir_y = static_cast<float>(unit.y());
    ray_hit.ray.dir_z = static_cast<float>(unit.z());
    ray_hit.ray.tnear = t_near;
    ray_hit.ray.tfar = floatAtLeast(span * (1.0 + 8.0 * static_cast<double>(FLT_EPSILON)) +
                                    8.0 * static_cast<double>(FLT_EPSILON) * impl_->half_extent);
    ray_hit.ray.time = 0.0f;
    ray_hit.ray.mask = 0xffffffffu;
    ray_hit.ray.id = 0;
    ray_hit.ray.flags = 0;
    ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    ray_hit.hit.primID = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(impl_->scene, &context, &ray_hit);
    if (ray_hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
      return result;
    }
    const int face = static_cast<int>(ray_hit.hit.primID);
    const Eigen::Vector3d& normal = impl_->mesh.face_normals[static_cast<std::size_t>(face)];
    // Refine Embree's float t on the exact (double) plane of the face.
    double t = static_cast<double>(ray_hit.ray.tfar);
    const double facing = normal.dot(unit);
    if (std::abs(facing) > 1e-9) {
      const double refined = normal.dot(impl_->vertex(face, 0) - start) / facing;
      if (std::isfinite(refined)) {
        t = refined;
      }
    }
    if (t <= 0.0) {
      t_near = std::nextafter(ray_hit.ray.tfar, std::numeric_limits<float>::infinity());
      continue;
    }
    if (t > span) {
      return result;
    }
    result.hit = true;
    result.face = face;
    result.t = t_min + t;
    result.point = origin + result.t * unit;
    result.normal = normal;
    return result;
  }
  return result;
}

}  // namespace freeform_inspection
