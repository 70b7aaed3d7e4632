// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/model_cache.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <system_error>
#include <type_traits>
#include <utility>

#include "io/file_util.h"
#include <unistd.h>

#include "freeform_inspection/content_hash.h"

#ifndef FREEFORM_INSPECTION_VERSION
#error "FREEFORM_INSPECTION_VERSION must be defined (CMakeLists.txt reads it from package.xml)"
#endif

namespace freeform_inspection {
namespace {

constexpr char kMagic[8] = {'F', 'I', 'M', 'O', 'D', 'E', 'L', 'C'};
// Bumped when the layout below changes; the package version covers changes of what is computed.
constexpr std::uint32_t kFormat = 5;

// Appends values to a byte buffer in the machine's own representation (the cache never leaves
// the machine that wrote it, and the version check refuses another build's file).
class Writer {
 public:
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "write the contents, not the object");
    const auto* bytes = reinterpret_cast<const char*>(&value);
    bytes_.append(bytes, sizeof(T));
  }
  template <typename T>
  void putVector(const std::vector<T>& values) {
    put<std::uint64_t>(values.size());
    for (const T& value : values) {
      put(value);
    }
  }
  void putPoints(const Points& points) {
    put<std::uint64_t>(points.size());
    for (const Eigen::Vector3d& p : points) {
      put(p.x());
      put(p.y());
      put(p.z());
    }
  }
  void putText(const std::string& text) {
    put<std::uint64_t>(text.size());
    bytes_.append(text);
  }
  void putStatus(const Status& status) {
    put(static_cast<std::int32_t>(status.code));
    putText(status.message);
  }
  void putMatrix(const Eigen::MatrixXd& matrix) {
    put<std::uint64_t>(static_cast<std::uint64_t>(matrix.rows()));
    put<std::uint64_t>(static_cast<std::uint64_t>(matrix.cols()));
    for (Eigen::Index i = 0; i < matrix.size(); ++i) {
      put(matrix.data()[i]);
    }
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

// Reads what Writer wrote. Every count is checked against the bytes left before anything is
// allocated; after the first failure every read fails and returns zeros.
class Reader {
 public:
  Reader(const char* data, std::size_t size) : data_(data), size_(size) {}

  bool ok() const { return ok_; }
  bool atEnd() const { return position_ == size_; }
  std::size_t position() const { return position_; }

  template <typename T>
  T get() {
    T value{};
    if (!take(sizeof(T))) {
      return value;
    }
    std::memcpy(&value, data_ + position_ - sizeof(T), sizeof(T));
    return value;
  }
  template <typename T>
  std::vector<T> getVector() {
    const std::uint64_t count = getCount(sizeof(T));
    std::vector<T> values;
    values.reserve(count);
    for (std::uint64_t i = 0; i < count && ok_; ++i) {
      values.push_back(get<T>());
    }
    return values;
  }
  Points getPoints() {
    const std::uint64_t count = getCount(3 * sizeof(double));
    Points points;
    points.reserve(count);
    for (std::uint64_t i = 0; i < count && ok_; ++i) {
      const double x = get<double>();
      const double y = get<double>();
      points.emplace_back(x, y, get<double>());
    }
    return points;
  }
  std::string getText() {
    const std::uint64_t count = getCount(1);
    if (!ok_) {
      return {};
    }
    std::string text(data_ + position_, count);
    position_ += count;
    return text;
  }
  Status getStatus() {
    const auto code = get<std::int32_t>();
    Status status;
    if (code < 0 || code > static_cast<std::int32_t>(StatusCode::kCancelled)) {
      ok_ = false;
      return status;
    }
    status.code = static_cast<StatusCode>(code);
    status.message = getText();
    return status;
  }
  Eigen::MatrixXd getMatrix() {
    const auto rows = get<std::uint64_t>();
    const auto cols = get<std::uint64_t>();
    const std::uint64_t left = (size_ - position_) / sizeof(double);
    if (!ok_ || (cols != 0 && rows > left / cols)) {
      ok_ = false;
      return {};
    }
    Eigen::MatrixXd matrix(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
    for (Eigen::Index i = 0; i < matrix.size(); ++i) {
      matrix.data()[i] = get<double>();
    }
    return matrix;
  }

  // A count of items of `item_size` bytes each, refused when the file cannot hold them.
  std::uint64_t getCount(std::size_t item_size) {
    const auto count = get<std::uint64_t>();
    if (!ok_ || count > (size_ - position_) / item_size) {
      ok_ = false;
      return 0;
    }
    return count;
  }

 private:
  bool take(std::size_t bytes) {
    if (!ok_ || bytes > size_ - position_) {
      ok_ = false;
      return false;
    }
    position_ += bytes;
    return true;
  }

  const char* data_;
  std::size_t size_;
  std::size_t position_ = 0;
  bool ok_ = true;
};

void putDescriptors(const DescriptorResult& d, Writer* out) {
  out->putStatus(d.status);
  out->putVector(d.radii);
  const CurvatureResult& c = d.curvature;
  out->putStatus(c.status);
  out->putVector(c.mean);
  out->putVector(c.gaussian);
  out->putVector(c.area);
  out->putPoints(c.normals);
  out->putPoints(c.on_plane);
  out->put<std::uint8_t>(c.signs_guessed ? 1 : 0);
  out->putVector(d.analysed);
  const SurfaceGraph& g = d.graph;
  out->putPoints(g.centroids);
  out->putPoints(g.normals);
  out->putVector(g.area);
  out->putVector(g.curvature);
  out->putVector(g.point_cell);
  out->putVector(g.offsets);
  out->putVector(g.neighbours);
  out->putVector(g.lengths);
  out->putMatrix(d.cell_values);
  out->putMatrix(d.cell_curvature);
  out->putVector(d.representative);
  out->put<std::int32_t>(d.cloud_neighbours);
  out->putPoints(d.on_quadric);
  out->put<std::uint64_t>(d.warnings.size());
  for (const std::string& warning : d.warnings) {
    out->putText(warning);
  }
}

void putPrepared(const ModelCacheEntry& e, Writer* out) {
  out->putPoints(e.mesh.vertices);
  out->put<std::uint64_t>(e.mesh.faces.size());
  for (const Eigen::Vector3i& f : e.mesh.faces) {
    out->put<std::int32_t>(f[0]);
    out->put<std::int32_t>(f[1]);
    out->put<std::int32_t>(f[2]);
  }
  out->putPoints(e.mesh.face_normals);
  out->put<std::uint64_t>(e.orientation.components);
  out->put<std::uint64_t>(e.orientation.flipped_faces);
  out->put<std::uint64_t>(e.orientation.reversed_components);
  const MeshTopology& t = e.topology;
  for (const std::size_t count : {t.edges,
                                  t.boundary_edges,
                                  t.non_manifold_edges,
                                  t.misoriented_edges,
                                  t.degenerate_faces,
                                  t.unused_vertices}) {
    out->put<std::uint64_t>(count);
  }
  out->put(t.signed_volume);
  out->put(t.area);
  out->putVector(e.face_border_edges);
  out->put<std::uint64_t>(e.load_warnings.size());
  for (const std::string& warning : e.load_warnings) {
    out->putText(warning);
  }
  out->putText(e.descriptor_key);
  out->putVector(e.chord_error.face);
  out->put(e.chord_error.max);
  for (int k = 0; k < 3; ++k) {
    out->put(e.chord_error.max_at[k]);
  }
  out->put(e.chord_error.curved_area_share);
  for (const std::array<double, 3>& bulge : e.chord_error.bulge) {
    for (const double q : bulge) {
      out->put(q);
    }
  }
}

void getPrepared(Reader* in, ModelCacheEntry* e) {
  e->mesh.vertices = in->getPoints();
  const std::uint64_t faces = in->getCount(3 * sizeof(std::int32_t));
  e->mesh.faces.reserve(faces);
  for (std::uint64_t i = 0; i < faces && in->ok(); ++i) {
    const auto a = in->get<std::int32_t>();
    const auto b = in->get<std::int32_t>();
    e->mesh.faces.emplace_back(a, b, in->get<std::int32_t>());
  }
  e->mesh.face_normals = in->getPoints();
  e->orientation.components = in->get<std::uint64_t>();
  e->orientation.flipped_faces = in->get<std::uint64_t>();
  e->orientation.reversed_components = in->get<std::uint64_t>();
  MeshTopology& t = e->topology;
  for (std::size_t* count : {&t.edges,
                             &t.boundary_edges,
                             &t.non_manifold_edges,
                             &t.misoriented_edges,
                             &t.degenerate_faces,
                             &t.unused_vertices}) {
    *count = in->get<std::uint64_t>();
  }
  t.signed_volume = in->get<double>();
  t.area = in->get<double>();
  e->face_border_edges = in->getVector<std::uint8_t>();
  const auto warnings = in->get<std::uint64_t>();
  for (std::uint64_t i = 0; i < warnings && in->ok(); ++i) {
    e->load_warnings.push_back(in->getText());
  }
  e->descriptor_key = in->getText();
  e->chord_error.face = in->getVector<double>();
  e->chord_error.max = in->get<double>();
  for (int k = 0; k < 3; ++k) {
    e->chord_error.max_at[k] = in->get<double>();
  }
  e->chord_error.curved_area_share = in->get<double>();
  e->chord_error.bulge.resize(e->chord_error.face.size());
  for (std::size_t f = 0; f < e->chord_error.bulge.size() && in->ok(); ++f) {
    for (double& q : e->chord_error.bulge[f]) {
      q = in->get<double>();
    }
  }
}

// Every face indexes a vertex and has its normal, so no later stage indexes past the mesh.
bool consistent(const TriangleMesh& mesh, const std::vector<std::uint8_t>& border_edges) {
  if (mesh.face_normals.size() != mesh.faces.size() ||
      !(border_edges.empty() || border_edges.size() == mesh.faces.size())) {
    return false;
  }
  const auto vertices = static_cast<std::int64_t>(mesh.vertices.size());
  return std::all_of(mesh.faces.begin(), mesh.faces.end(), [vertices](const Eigen::Vector3i& f) {
    return f.minCoeff() >= 0 && f.maxCoeff() < vertices;
  });
}

DescriptorResult getDescriptors(Reader* in) {
  DescriptorResult d;
  d.status = in->getStatus();
  d.radii = in->getVector<double>();
  CurvatureResult& c = d.curvature;
  c.status = in->getStatus();
  c.mean = in->getVector<double>();
  c.gaussian = in->getVector<double>();
  c.area = in->getVector<double>();
  c.normals = in->getPoints();
  c.on_plane = in->getPoints();
  c.signs_guessed = in->get<std::uint8_t>() != 0;
  d.analysed = in->getVector<int>();
  SurfaceGraph& g = d.graph;
  g.centroids = in->getPoints();
  g.normals = in->getPoints();
  g.area = in->getVector<double>();
  g.curvature = in->getVector<double>();
  g.point_cell = in->getVector<int>();
  g.offsets = in->getVector<std::size_t>();
  g.neighbours = in->getVector<int>();
  g.lengths = in->getVector<double>();
  d.cell_values = in->getMatrix();
  d.cell_curvature = in->getMatrix();
  d.representative = in->getVector<int>();
  d.cloud_neighbours = in->get<std::int32_t>();
  d.on_quadric = in->getPoints();
  const auto warnings = in->get<std::uint64_t>();
  for (std::uint64_t i = 0; i < warnings && in->ok(); ++i) {
    d.warnings.push_back(in->getText());
  }
  return d;
}

// The graph's arrays agree with each other, so no later stage indexes past one of them.
bool consistent(const DescriptorResult& d) {
  const SurfaceGraph& g = d.graph;
  const std::size_t cells = g.size();
  if (g.normals.size() != cells || g.area.size() != cells || g.curvature.size() != cells ||
      g.offsets.size() != cells + 1 || g.offsets.front() != 0 ||
      g.offsets.back() != g.neighbours.size() || g.lengths.size() != g.neighbours.size() ||
      static_cast<std::size_t>(d.cell_values.rows()) != cells ||
      static_cast<std::size_t>(d.cell_values.cols()) != d.radii.size() ||
      d.cell_curvature.rows() != d.cell_values.rows() ||
      d.cell_curvature.cols() != d.cell_values.cols()) {
    return false;
  }
  for (std::size_t c = 0; c < cells; ++c) {
    if (g.offsets[c] > g.offsets[c + 1]) {
      return false;
    }
  }
  for (const int n : g.neighbours) {
    if (n < 0 || static_cast<std::size_t>(n) >= cells) {
      return false;
    }
  }
  for (const int cell : g.point_cell) {
    if (cell < -1 || cell >= static_cast<int>(cells)) {
      return false;
    }
  }
  return true;
}

ModelCacheRead unusable(const std::string& file, const std::string& reason) {
  ModelCacheRead read;
  read.status = Status::failure(StatusCode::kInvalidInput,
                                "model cache file '" + file + "' is unusable: " + reason);
  return read;
}

}  // namespace

const char* packageVersion() {
  return FREEFORM_INSPECTION_VERSION;
}

std::string modelCacheFile(const std::string& directory, const std::string& key) {
  return (std::filesystem::path(directory) / (key + ".fimodel")).string();
}

std::string modelFileKey(std::string_view file_bytes,
                         double scale,
                         const std::string& settings_key) {
  ContentHash hash;
  hash.addBytes(file_bytes.data(), file_bytes.size());
  hash.add(scale);
  hash.addText(settings_key);
  return hash.hex();
}

Status writeModelCache(const std::string& directory,
                       const std::string& key,
                       const ModelCacheEntry& entry) {
  Writer payload;
  putPrepared(entry, &payload);
  putDescriptors(entry.descriptors, &payload);
  payload.put<std::uint64_t>(entry.symmetries.size());
  for (const Symmetry& symmetry : entry.symmetries) {
    for (int i = 0; i < 16; ++i) {
      payload.put(symmetry.S.matrix().data()[i]);
    }
    payload.put(symmetry.score);
  }
  payload.put(entry.thickness);
  payload.put<std::uint64_t>(entry.normal_frame_turns.size());
  for (const Eigen::Isometry3d& turn : entry.normal_frame_turns) {
    for (int i = 0; i < 16; ++i) {
      payload.put(turn.matrix().data()[i]);
    }
  }
  ContentHash checksum;
  checksum.addBytes(payload.bytes().data(), payload.bytes().size());
  Writer header;
  header.put(kMagic);
  header.put(kFormat);
  header.putText(FREEFORM_INSPECTION_VERSION);
  header.putText(key);
  header.put<std::uint64_t>(payload.bytes().size());
  header.put(checksum.value());

  const std::string file = modelCacheFile(directory, key);
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    return Status::failure(
        StatusCode::kInvalidInput,
        "cannot create the model cache directory '" + directory + "': " + error.message());
  }
  // A name of this process's own, so two processes writing the same model do not mix.
  const std::string temporary = file + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(header.bytes().data(), static_cast<std::streamsize>(header.bytes().size()));
    out.write(payload.bytes().data(), static_cast<std::streamsize>(payload.bytes().size()));
    if (!out.flush()) {
      std::filesystem::remove(temporary, error);
      return Status::failure(StatusCode::kInvalidInput,
                             "cannot write the model cache file '" + temporary + "'");
    }
  }
  std::filesystem::rename(temporary, file, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    return Status::failure(StatusCode::kInvalidInput,
                           "cannot write the model cache file '" + file + "'");
  }
  return Status::success();
}

ModelCacheRead readModelCache(const std::string& directory, const std::string& key) {
  const std::string file = modelCacheFile(directory, key);
  std::error_code error;
  if (!std::filesystem::exists(file, error)) {
    ModelCacheRead read;
    read.missing = true;
    read.status = Status::failure(StatusCode::kInvalidInput, "no model cache file '" + file + "'");
    return read;
  }
  io_internal::FileBytes file_bytes;
  if (!io_internal::readWholeFile(file, &file_bytes).ok()) {
    return unusable(file, "it cannot be read");
  }
  const std::string_view bytes = file_bytes.view();
  Reader header(bytes.data(), bytes.size());
  const auto magic = header.get<std::array<char, sizeof(kMagic)>>();
  if (!header.ok() || std::memcmp(magic.data(), kMagic, sizeof(kMagic)) != 0) {
    return unusable(file, "not a model cache file");
  }
  if (header.get<std::uint32_t>() != kFormat) {
    return unusable(file, "another format");
  }
  const std::string version = header.getText();
  if (version != FREEFORM_INSPECTION_VERSION) {
    return unusable(file,
                    "written by version " + version + ", this is " + FREEFORM_INSPECTION_VERSION);
  }
  if (header.getText() != key) {
    return unusable(file, "it holds another model or settings");
  }
  const auto size = header.get<std::uint64_t>();
  const auto expected = header.get<std::uint64_t>();
  const std::size_t start = header.position();
  if (!header.ok() || bytes.size() - start != size) {
    return unusable(file, bytes.size() - start < size ? "truncated" : "it has trailing bytes");
  }
  ContentHash checksum;
  checksum.addBytes(bytes.data() + start, size);
  if (checksum.value() != expected) {
    return unusable(file, "its checksum does not match (damaged)");
  }
  Reader payload(bytes.data() + start, size);
  ModelCacheEntry entry;
  getPrepared(&payload, &entry);
  entry.descriptors = getDescriptors(&payload);
  const auto symmetries = payload.get<std::uint64_t>();
  for (std::uint64_t s = 0; s < symmetries && payload.ok(); ++s) {
    Symmetry symmetry;
    for (int i = 0; i < 16; ++i) {
      symmetry.S.matrix().data()[i] = payload.get<double>();
    }
    symmetry.score = payload.get<double>();
    entry.symmetries.push_back(symmetry);
  }
  entry.thickness = payload.get<double>();
  const auto turns = payload.get<std::uint64_t>();
  for (std::uint64_t t = 0; t < turns && payload.ok(); ++t) {
    Eigen::Isometry3d turn;
    for (int i = 0; i < 16; ++i) {
      turn.matrix().data()[i] = payload.get<double>();
    }
    entry.normal_frame_turns.push_back(turn);
  }
  if (!payload.ok() || !payload.atEnd() || !consistent(entry.descriptors) ||
      !consistent(entry.mesh, entry.face_border_edges) ||
      entry.chord_error.face.size() != entry.mesh.faces.size()) {
    return unusable(file, "its contents do not fit together");
  }
  ModelCacheRead read;
  read.entry = std::move(entry);
  return read;
}

}  // namespace freeform_inspection
