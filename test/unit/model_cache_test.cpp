// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/model_cache.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/pipeline.h"
#include "freeform_inspection/synthetic_scan.h"

namespace freeform_inspection {
namespace {

const std::string kBlade = std::string(FREEFORM_DATA_DIR) + "/blade/blade.stl";

// A directory of the test's own, empty.
std::string freshDirectory(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / ("model_cache_test_" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Every field of the descriptors, compared exactly: the cache must give the bits it was given.
void expectSameDescriptors(const DescriptorResult& a, const DescriptorResult& b) {
  EXPECT_EQ(a.status.code, b.status.code);
  EXPECT_EQ(a.radii, b.radii);
  EXPECT_EQ(a.curvature.mean, b.curvature.mean);
  EXPECT_EQ(a.curvature.gaussian, b.curvature.gaussian);
  EXPECT_EQ(a.curvature.area, b.curvature.area);
  EXPECT_EQ(a.curvature.normals, b.curvature.normals);
  EXPECT_EQ(a.curvature.on_plane, b.curvature.on_plane);
  EXPECT_EQ(a.curvature.signs_guessed, b.curvature.signs_guessed);
  EXPECT_EQ(a.analysed, b.analysed);
  EXPECT_EQ(a.graph.centroids, b.graph.centroids);
  EXPECT_EQ(a.graph.normals, b.graph.normals);
  EXPECT_EQ(a.graph.area, b.graph.area);
  EXPECT_EQ(a.graph.curvature, b.graph.curvature);
  EXPECT_EQ(a.graph.point_cell, b.graph.point_cell);
  EXPECT_EQ(a.graph.offsets, b.graph.offsets);
  EXPECT_EQ(a.graph.neighbours, b.graph.neighbours);
  EXPECT_EQ(a.graph.lengths, b.graph.lengths);
  EXPECT_EQ(a.cell_values, b.cell_values);
  EXPECT_EQ(a.cell_curvature, b.cell_curvature);
  EXPECT_EQ(a.representative, b.representative);
  EXPECT_EQ(a.cloud_neighbours, b.cloud_neighbours);
  EXPECT_EQ(a.on_quadric, b.on_quadric);
  EXPECT_EQ(a.warnings, b.warnings);
}

// The cache file a load of `path` at `scale` with the default settings uses.
std::string cacheFileOf(const std::string& dir, const std::string& path, double scale) {
  return modelCacheFile(dir, modelFileKey(readBytes(path), scale, descriptorSettingsKey({})));
}

// The prepared mesh and what was found about it, compared exactly.
void expectSameMesh(const Model& a, const Model& b) {
  EXPECT_EQ(a.mesh().vertices, b.mesh().vertices);
  EXPECT_EQ(a.mesh().faces, b.mesh().faces);
  EXPECT_EQ(a.mesh().face_normals, b.mesh().face_normals);
  EXPECT_EQ(a.faceBorderEdges(), b.faceBorderEdges());
  EXPECT_EQ(a.orientation().components, b.orientation().components);
  EXPECT_EQ(a.orientation().flipped_faces, b.orientation().flipped_faces);
  EXPECT_EQ(a.orientation().reversed_components, b.orientation().reversed_components);
  EXPECT_EQ(a.topology().edges, b.topology().edges);
  EXPECT_EQ(a.topology().boundary_edges, b.topology().boundary_edges);
  EXPECT_EQ(a.topology().degenerate_faces, b.topology().degenerate_faces);
  EXPECT_EQ(a.topology().signed_volume, b.topology().signed_volume);
  EXPECT_EQ(a.topology().area, b.topology().area);
  EXPECT_EQ(a.bounds().min, b.bounds().min);
  EXPECT_EQ(a.bounds().max, b.bounds().max);
  EXPECT_EQ(a.descriptorKey(), b.descriptorKey());
  EXPECT_EQ(a.thickness(), b.thickness());
  EXPECT_GT(a.thickness(), 0.0);
  ASSERT_EQ(a.normalFrameTurns().size(), b.normalFrameTurns().size());
  EXPECT_FALSE(a.normalFrameTurns().empty());
  for (std::size_t t = 0; t < a.normalFrameTurns().size(); ++t) {
    EXPECT_EQ(a.normalFrameTurns()[t].matrix(), b.normalFrameTurns()[t].matrix());
  }
}

const Model& blade() {
  static const std::shared_ptr<const Model> kModel = [] {
    const ModelLoadResult loaded = loadModel(kBlade, 0.001, "blade");
    EXPECT_TRUE(loaded.status.ok()) << loaded.status.message;
    return loaded.model;
  }();
  return *kModel;
}

TEST(ModelCache, AnEntryReadsBackBitForBit) {
  const std::string dir = freshDirectory("round_trip");
  ASSERT_TRUE(
      writeModelCache(dir, "0011223344556677", blade().cacheEntry({"a load warning"})).ok());
  const ModelCacheRead read = readModelCache(dir, "0011223344556677");
  ASSERT_TRUE(read.status.ok()) << read.status.message;
  ASSERT_TRUE(read.entry.has_value());
  EXPECT_EQ(read.entry->load_warnings, std::vector<std::string>{"a load warning"});
  expectSameDescriptors(read.entry->descriptors, blade().descriptors());
  expectSameMesh(Model(*read.entry, "blade", kBlade, DescriptorConfig()), blade());
  ASSERT_EQ(read.entry->symmetries.size(), blade().symmetries().size());
  for (std::size_t s = 0; s < blade().symmetries().size(); ++s) {
    EXPECT_EQ(read.entry->symmetries[s].S.matrix(), blade().symmetries()[s].S.matrix());
    EXPECT_EQ(read.entry->symmetries[s].score, blade().symmetries()[s].score);
  }
}

TEST(ModelCache, SecondLoadComesFromTheCacheAndInspectsTheSame) {
  const std::string dir = freshDirectory("load");
  const ModelLoadResult first = loadModel(kBlade, 0.001, "blade", DescriptorConfig(), dir);
  ASSERT_TRUE(first.status.ok()) << first.status.message;
  EXPECT_FALSE(first.model->fromCache());
  EXPECT_TRUE(first.warnings.empty());
  EXPECT_TRUE(std::filesystem::exists(cacheFileOf(dir, kBlade, 0.001)));
  const ModelLoadResult second = loadModel(kBlade, 0.001, "blade", DescriptorConfig(), dir);
  ASSERT_TRUE(second.status.ok()) << second.status.message;
  EXPECT_TRUE(second.model->fromCache());
  EXPECT_TRUE(second.warnings.empty());
  expectSameDescriptors(second.model->descriptors(), first.model->descriptors());
  expectSameMesh(*second.model, *first.model);
  // The same scan inspected with either model: the same pose and numbers to the last bit.
  SyntheticScanConfig config;
  config.points = 8000;
  config.noise_ratio = 0.002;
  config.seed = 5;
  const SyntheticScan scan = makeSyntheticScan(first.model->query(), config);
  const InspectionResult a = inspect(*first.model, scan.scan, PipelineConfig());
  const InspectionResult b = inspect(*second.model, scan.scan, PipelineConfig());
  ASSERT_EQ(a.registration, RegistrationStatus::kOk) << a.status.message;
  EXPECT_EQ(b.registration, a.registration);
  EXPECT_EQ(b.T_cad_scan.matrix(), a.T_cad_scan.matrix());
  EXPECT_EQ(b.rmse, a.rmse);
  EXPECT_EQ(b.deviation.rms, a.deviation.rms);
  // Other descriptor settings are another key: computed, not read.
  DescriptorConfig other;
  other.cell_ratio = 0.7;
  const ModelLoadResult third = loadModel(kBlade, 0.001, "blade", other, dir);
  ASSERT_TRUE(third.status.ok()) << third.status.message;
  EXPECT_FALSE(third.model->fromCache());
  EXPECT_NE(third.model->descriptorKey(), first.model->descriptorKey());
  // Another unit scale is another key too.
  EXPECT_FALSE(loadModel(kBlade, 0.0254, "blade", DescriptorConfig(), dir).model->fromCache());
}

// What loading the file said, and what was turned on it, is said again when it comes from the
// cache: a CAD with an inward face and a triangle whose corners coincide.
TEST(ModelCache, ACachedModelSaysWhatItsFileSaid) {
  const std::string dir = freshDirectory("warnings");
  std::filesystem::create_directories(dir);
  TriangleMesh mesh = loadMesh(kBlade, 1.0).mesh;
  std::swap(mesh.faces[7][1], mesh.faces[7][2]);
  mesh.faces.emplace_back(mesh.faces[3][0], mesh.faces[3][0], mesh.faces[3][1]);
  mesh.face_normals.emplace_back(Eigen::Vector3d::Zero());
  const std::string path = dir + "/flawed.stl";
  ASSERT_TRUE(saveMeshStl(path, mesh).ok());
  const ModelLoadResult first =
      loadModel(path, 0.001, "flawed", DescriptorConfig(), dir + "/cache");
  ASSERT_TRUE(first.status.ok()) << first.status.message;
  ASSERT_FALSE(first.model->fromCache());
  ASSERT_EQ(first.warnings.size(), 2u);
  EXPECT_NE(first.warnings[0].find("dropped 1 STL triangles"), std::string::npos)
      << first.warnings[0];
  EXPECT_NE(first.warnings[1].find("1 faces were wound inward"), std::string::npos)
      << first.warnings[1];
  const ModelLoadResult second =
      loadModel(path, 0.001, "flawed", DescriptorConfig(), dir + "/cache");
  ASSERT_TRUE(second.status.ok()) << second.status.message;
  EXPECT_TRUE(second.model->fromCache());
  EXPECT_EQ(second.warnings, first.warnings);
  expectSameMesh(*second.model, *first.model);
  // The file changed (one vertex moved by a micrometre): its old entry is not used.
  mesh.vertices[0].x() += 0.001;
  ASSERT_TRUE(saveMeshStl(path, mesh).ok());
  const ModelLoadResult changed =
      loadModel(path, 0.001, "flawed", DescriptorConfig(), dir + "/cache");
  ASSERT_TRUE(changed.status.ok()) << changed.status.message;
  EXPECT_FALSE(changed.model->fromCache());
  EXPECT_NE(changed.model->mesh().vertices, first.model->mesh().vertices);
}

TEST(ModelCache, MissingDamagedAndForeignFilesAreRefusedWithAReason) {
  const std::string dir = freshDirectory("refused");
  const std::string key = "8899aabbccddeeff";
  const ModelCacheRead missing = readModelCache(dir, key);
  EXPECT_TRUE(missing.missing);
  EXPECT_FALSE(missing.entry.has_value());
  ASSERT_TRUE(writeModelCache(dir, key, blade().cacheEntry({})).ok());
  const std::string file = modelCacheFile(dir, key);
  const std::string good = readBytes(file);
  const auto refusedFor = [&](const std::string& bytes, const std::string& reason) {
    writeBytes(file, bytes);
    const ModelCacheRead read = readModelCache(dir, key);
    EXPECT_FALSE(read.entry.has_value()) << reason;
    EXPECT_FALSE(read.missing) << reason;
    EXPECT_NE(read.status.message.find(reason), std::string::npos) << read.status.message;
  };
  refusedFor("not a cache file at all", "not a model cache file");
  std::string flipped = good;
  flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x10);
  refusedFor(flipped, "checksum does not match");
  refusedFor(good.substr(0, good.size() - 1), "truncated");
  refusedFor(good + "x", "trailing bytes");
  // Cut anywhere (every length through the header, then twenty more): refused, never a crash
  // or a huge allocation from a count read half-way.
  for (std::size_t length = 0; length < good.size();
       length += length < 200 ? 1 : good.size() / 20) {
    writeBytes(file, good.substr(0, length));
    EXPECT_FALSE(readModelCache(dir, key).entry.has_value()) << "cut at " << length;
  }
  // The same file under another key (another model or settings), or from another version.
  writeBytes(file, good);
  writeBytes(modelCacheFile(dir, "0123456789abcdef"), good);
  const ModelCacheRead foreign = readModelCache(dir, "0123456789abcdef");
  EXPECT_NE(foreign.status.message.find("another model"), std::string::npos)
      << foreign.status.message;
  std::string other_version = good;
  const std::size_t at = other_version.find(packageVersion());
  ASSERT_NE(at, std::string::npos);
  other_version[at] = other_version[at] == '9' ? '8' : '9';
  refusedFor(other_version, "written by version");
  // Whole and checksummed, but a graph whose links point past its cells (a writer's bug): no
  // later stage may index with it.
  ModelCacheEntry broken = blade().cacheEntry({});
  broken.descriptors.graph.neighbours.front() = static_cast<int>(broken.descriptors.graph.size());
  ASSERT_TRUE(writeModelCache(dir, "feedfacefeedface", broken).ok());
  const ModelCacheRead inconsistent = readModelCache(dir, "feedfacefeedface");
  EXPECT_FALSE(inconsistent.entry.has_value());
  EXPECT_NE(inconsistent.status.message.find("do not fit together"), std::string::npos)
      << inconsistent.status.message;
  // ... or a face whose corner is past the vertices.
  ModelCacheEntry past = blade().cacheEntry({});
  past.mesh.faces.back()[2] = static_cast<int>(past.mesh.vertices.size());
  ASSERT_TRUE(writeModelCache(dir, "feedfacefeedfac0", past).ok());
  const ModelCacheRead outside = readModelCache(dir, "feedfacefeedfac0");
  EXPECT_FALSE(outside.entry.has_value());
  EXPECT_NE(outside.status.message.find("do not fit together"), std::string::npos)
      << outside.status.message;
}

TEST(ModelCache, UnusableCacheCostsAWarningNeverTheLoad) {
  const std::string dir = freshDirectory("unusable");
  ASSERT_TRUE(loadModel(kBlade, 0.001, "blade", DescriptorConfig(), dir).status.ok());
  const std::string file = cacheFileOf(dir, kBlade, 0.001);
  writeBytes(file, "damaged");
  const ModelLoadResult damaged = loadModel(kBlade, 0.001, "blade", DescriptorConfig(), dir);
  ASSERT_TRUE(damaged.status.ok()) << damaged.status.message;
  EXPECT_FALSE(damaged.model->fromCache());
  ASSERT_EQ(damaged.warnings.size(), 1u);
  EXPECT_NE(damaged.warnings.front().find("computed again"), std::string::npos)
      << damaged.warnings.front();
  // ... and rewritten: the next load reads it.
  EXPECT_TRUE(loadModel(kBlade, 0.001, "blade", DescriptorConfig(), dir).model->fromCache());
  // A directory that cannot be made (a file stands where it should be).
  const std::string blocked = freshDirectory("blocked");
  writeBytes(blocked, "a file, not a directory");
  const ModelLoadResult unwritable =
      loadModel(kBlade, 0.001, "blade", DescriptorConfig(), blocked + "/models");
  ASSERT_TRUE(unwritable.status.ok()) << unwritable.status.message;
  ASSERT_EQ(unwritable.warnings.size(), 1u);
  EXPECT_NE(unwritable.warnings.front().find("cannot create the model cache directory"),
            std::string::npos)
      << unwritable.warnings.front();
}

}  // namespace
}  // namespace freeform_inspection
