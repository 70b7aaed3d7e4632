// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// The virtual scanner on shapes with known answers: a sphere (silhouette disc, grazing cut-off,
// range noise), a box face (dents and bumps), and the shipped blade (a scan that the pipeline
// registers). Seeds are fixed and named in every failure message.
#include "freeform_inspection/virtual_scanner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "analytic_shapes.h"
#include "test_shapes.h"
#include <gtest/gtest.h>
#include <omp.h>
#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>
#include <unistd.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/pipeline.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSphereRadius = 0.05;  // [m]
constexpr int kSphereSubdivisions = 5;  // 20 480 faces

const MeshQuery& sphere() {
  static const MeshQuery kQuery(test::icosphere(kSphereRadius, kSphereSubdivisions));
  return kQuery;
}

// A pose that puts the CAD origin on the optical axis at `depth`, rotated by `rotation`.
Eigen::Isometry3d onAxis(double depth, const Eigen::Matrix3d& rotation) {
  Eigen::Isometry3d T_sensor_cad = Eigen::Isometry3d::Identity();
  T_sensor_cad.linear() = rotation;
  T_sensor_cad.translation() = Eigen::Vector3d(0.0, 0.0, depth);
  return T_sensor_cad;
}

VirtualScannerConfig smallCamera(std::uint64_t seed) {
  VirtualScannerConfig config;
  config.width = 320;
  config.height = 240;
  config.seed = seed;
  return config;
}

VirtualScan scan(const MeshQuery& cad, const VirtualScannerConfig& config) {
  VirtualScan made = makeVirtualScan(cad, config);
  EXPECT_TRUE(made.status.ok()) << made.status.message;
  return made;
}

std::size_t finiteCount(const Scan& s) {
  return static_cast<std::size_t>(std::count_if(
      s.points.begin(), s.points.end(), [](const Eigen::Vector3d& p) { return p.allFinite(); }));
}

// Pixels whose ray meets the sphere at an incidence up to `max_incidence` (rad) from a pinhole at
// distance D from the centre: sin β = (R/D)·sin θ (law of sines in the triangle sensor–centre–
// hit), a disc of radius f·tan β pixels about the principal point.
double expectedDiscPixels(double focal, double distance, double max_incidence) {
  const double beta = std::asin(kSphereRadius / distance * std::sin(max_incidence));
  return kPi * std::pow(focal * std::tan(beta), 2);
}

// How far the icosphere's facets dip below the sphere: R minus the smallest distance of a face's
// plane from the centre (the foot of the perpendicular lies inside these near-equilateral faces).
double facetSagitta() {
  const TriangleMesh& mesh = sphere().mesh();
  double sagitta = 0.0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Eigen::Vector3d& corner = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][0])];
    sagitta = std::max(sagitta, kSphereRadius - std::abs(mesh.face_normals[f].dot(corner)));
  }
  return sagitta;
}

double focalOf(const VirtualScannerConfig& config) {
  return 0.5 * config.width / std::tan(0.5 * config.horizontal_fov_deg * kPi / 180.0);
}

TEST(VirtualScanner, DefaultConfigValidates) {
  EXPECT_TRUE(validate(VirtualScannerConfig()).empty());
}

TEST(VirtualScanner, OrganizedScanWithTruthOntoTheSurface) {
  const VirtualScannerConfig config = smallCamera(11);
  SCOPED_TRACE("seed 11");
  const VirtualScan made = scan(sphere(), config);
  ASSERT_TRUE(made.scan.isOrganized());
  EXPECT_EQ(made.scan.width, 320);
  EXPECT_EQ(made.scan.height, 240);
  EXPECT_TRUE(made.scan.normals.empty());
  EXPECT_TRUE(made.scan.faces.empty());
  ASSERT_EQ(made.pixels.size(), made.scan.points.size());
  const VirtualScanCounts& c = made.counts;
  EXPECT_EQ(c.valid + c.outliers + c.misses + c.out_of_range + c.grazing + c.dropouts,
            made.scan.points.size());
  EXPECT_EQ(finiteCount(made.scan), c.valid);
  double worst = 0.0;
  double worst_sphere = 0.0;
  for (std::size_t i = 0; i < made.scan.points.size(); ++i) {
    const Eigen::Vector3d& p = made.scan.points[i];
    ASSERT_EQ(p.allFinite(), made.pixels[i] == PixelOutcome::kValid) << "pixel " << i;
    if (!p.allFinite()) {
      continue;
    }
    EXPECT_GT(p.z(), 0.0);  // in front of the sensor
    const Eigen::Vector3d in_cad = made.T_cad_scan * p;
    worst = std::max(worst, std::abs(sphere().closest(in_cad).signed_distance));
    worst_sphere = std::max(worst_sphere, std::abs(in_cad.norm() - kSphereRadius));
  }
  std::printf(
      "noise-free sphere: %zu points, worst distance to the CAD %.3g m, to the sphere %.3g m "
      "(facet sagitta %.3g m)\n",
      c.valid,
      worst,
      worst_sphere,
      facetSagitta());
  EXPECT_LT(worst, 1e-9);  // ray hits lie on the triangles (double rounding only)
  EXPECT_LT(worst_sphere, facetSagitta() + 1e-12);
}

TEST(VirtualScanner, RandomPoseFillsTheImageAsConfigured) {
  VirtualScannerConfig config = smallCamera(12);
  config.fill_ratio = 0.5;
  config.max_incidence_deg = 90.0;
  SCOPED_TRACE("seed 12");
  const VirtualScan made = scan(sphere(), config);
  const double diagonal = computeBoundingBox(sphere().mesh().vertices).diagonal();
  const double focal = focalOf(config);
  // The bounding sphere (radius L/2) projects onto fill × half the smaller side.
  EXPECT_NEAR(made.working_distance, diagonal * focal / (0.5 * 240), 1e-12);
  const double expected = expectedDiscPixels(focal, made.working_distance, 0.5 * kPi);
  std::printf("sphere at %.4f m: %zu pixels, disc %.1f\n",
              made.working_distance,
              made.counts.valid,
              expected);
  EXPECT_NEAR(static_cast<double>(made.counts.valid), expected, 0.02 * expected);
  EXPECT_EQ(made.counts.grazing, 0u);
  EXPECT_EQ(made.counts.valid + made.counts.misses, made.scan.points.size());
}

TEST(VirtualScanner, SilhouetteAndGrazingCutOffMatchTheDisc) {
  for (const double max_incidence_deg : {90.0, 80.0, 60.0}) {
    VirtualScannerConfig config = smallCamera(13);
    config.random_pose = false;
    config.T_sensor_cad = onAxis(0.25, Eigen::Matrix3d::Identity());
    config.max_incidence_deg = max_incidence_deg;
    SCOPED_TRACE("seed 13, max incidence " + std::to_string(max_incidence_deg));
    const VirtualScan made = scan(sphere(), config);
    const double focal = focalOf(config);
    const double disc = expectedDiscPixels(focal, 0.25, 0.5 * kPi);
    const double seen = expectedDiscPixels(focal, 0.25, max_incidence_deg * kPi / 180.0);
    std::printf("max incidence %2.0f°: %zu valid (expected %.1f), %zu grazing (expected %.1f)\n",
                max_incidence_deg,
                made.counts.valid,
                seen,
                made.counts.grazing,
                disc - seen);
    EXPECT_NEAR(static_cast<double>(made.counts.valid), seen, 0.02 * seen);
    EXPECT_NEAR(static_cast<double>(made.counts.valid + made.counts.grazing), disc, 0.02 * disc);
  }
}

TEST(VirtualScanner, RangeNoiseHasTheConfiguredSigma) {
  for (const std::uint64_t seed : {21u, 22u}) {
    VirtualScannerConfig config = smallCamera(seed);
    config.noise_sigma = 5e-4;
    SCOPED_TRACE("seed " + std::to_string(seed));
    const VirtualScan made = scan(sphere(), config);
    EXPECT_EQ(made.noise_sigma, 5e-4);
    // The pinhole is at the origin, so a point's own direction is its pixel's ray: the noise is
    // its range minus the range of the noise-free hit on that ray.
    const Eigen::Isometry3d& T_cad_scan = made.T_cad_scan;
    double sum = 0.0;
    double sum2 = 0.0;
    std::size_t n = 0;
    for (const Eigen::Vector3d& p : made.scan.points) {
      if (!p.allFinite()) {
        continue;
      }
      const RayHit hit =
          sphere().castRay(T_cad_scan.translation(), T_cad_scan.linear() * p.normalized());
      ASSERT_TRUE(hit.hit);
      const double residual = p.norm() - hit.t;
      sum += residual;
      sum2 += residual * residual;
      ++n;
    }
    const double mean = sum / static_cast<double>(n);
    const double sigma = std::sqrt(sum2 / static_cast<double>(n) - mean * mean);
    std::printf("seed %lu: %zu points, range noise mean %.3g m, σ %.4g m (configured 5e-4)\n",
                static_cast<unsigned long>(seed),
                n,
                mean,
                sigma);
    EXPECT_NEAR(sigma, 5e-4, 0.1 * 5e-4);
    EXPECT_LT(std::abs(mean), 5.0 * 5e-4 / std::sqrt(static_cast<double>(n)));
  }
}

TEST(VirtualScanner, NoiseRatioScalesWithTheDiagonal) {
  VirtualScannerConfig config = smallCamera(23);
  config.noise_ratio = 0.002;
  const VirtualScan made = scan(sphere(), config);
  const double diagonal = computeBoundingBox(sphere().mesh().vertices).diagonal();
  EXPECT_DOUBLE_EQ(made.noise_sigma, 0.002 * diagonal);
  // Every point stays within 6 σ of the surface (along the ray, so less along the normal).
  for (const Eigen::Vector3d& p : made.scan.points) {
    if (p.allFinite()) {
      ASSERT_LT(std::abs(sphere().closest(made.T_cad_scan * p).signed_distance),
                6.0 * made.noise_sigma);
    }
  }
}

TEST(VirtualScanner, DropoutsRemoveTheConfiguredShareOfReturns) {
  constexpr double kDropout = 0.3;
  VirtualScannerConfig config = smallCamera(31);
  const VirtualScan clean = scan(sphere(), config);
  config.dropout_probability = kDropout;
  SCOPED_TRACE("seed 31");
  const VirtualScan dropped = scan(sphere(), config);
  const double returns = static_cast<double>(dropped.counts.valid + dropped.counts.dropouts);
  const double share = static_cast<double>(dropped.counts.dropouts) / returns;
  const double binomial = std::sqrt(kDropout * (1.0 - kDropout) / returns);
  std::printf("dropout: %.4f of %.0f returns (configured %.2f, binomial σ %.4f)\n",
              share,
              returns,
              kDropout,
              binomial);
  EXPECT_NEAR(share, kDropout, 4.0 * binomial);
  // Same seed: the same returns, minus the dropped ones, at the same coordinates.
  EXPECT_EQ(clean.counts.valid, dropped.counts.valid + dropped.counts.dropouts);
  for (std::size_t i = 0; i < clean.pixels.size(); ++i) {
    if (dropped.pixels[i] == PixelOutcome::kValid) {
      ASSERT_EQ(clean.scan.points[i], dropped.scan.points[i]) << "pixel " << i;
    } else if (dropped.pixels[i] == PixelOutcome::kDropout) {
      ASSERT_EQ(clean.pixels[i], PixelOutcome::kValid) << "pixel " << i;
    }
  }
}

TEST(VirtualScanner, OutliersAreTheConfiguredShareNearThePart) {
  constexpr double kOutliers = 0.05;
  VirtualScannerConfig config = smallCamera(32);
  config.outlier_fraction = kOutliers;
  SCOPED_TRACE("seed 32");
  const VirtualScan made = scan(sphere(), config);
  const double pixels = static_cast<double>(made.pixels.size());
  const double share = static_cast<double>(made.counts.outliers) / pixels;
  std::printf("outliers: %.4f of the pixels (configured %.2f)\n", share, kOutliers);
  EXPECT_NEAR(share, kOutliers, 4.0 * std::sqrt(kOutliers * (1.0 - kOutliers) / pixels));
  EXPECT_EQ(finiteCount(made.scan), made.counts.valid + made.counts.outliers);
  const double radius = 0.5 * computeBoundingBox(sphere().mesh().vertices).diagonal();
  for (std::size_t i = 0; i < made.pixels.size(); ++i) {
    if (made.pixels[i] == PixelOutcome::kOutlier) {
      ASSERT_NEAR(made.scan.points[i].norm(), made.working_distance, radius + 1e-12);
    }
  }
}

// The box's +z face (z = 0.02) faces the sensor 0.4 m away.
struct BoxCase {
  MeshQuery cad{test::makeBox(Eigen::Vector3d(0.1, 0.05, 0.02))};
  VirtualScannerConfig config;
  BoxCase() {
    config = smallCamera(41);
    config.random_pose = false;
    config.T_sensor_cad =
        onAxis(0.4, Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).toRotationMatrix());
    config.noise_sigma = 1e-5;
  }
};

TEST(VirtualScanner, DentsAndBumpsDisplaceAlongTheNormal) {
  for (const double depth : {-5e-4, 3e-4}) {
    BoxCase box;
    SurfaceDefect defect;
    defect.centre = Eigen::Vector3d(0.01, -0.005, 0.02);
    defect.radius = 0.012;
    defect.depth = depth;
    box.config.defects = {defect};
    SCOPED_TRACE("seed 41, depth " + std::to_string(depth));
    const VirtualScan made = scan(box.cad, box.config);
    double nearest = 1.0;
    double at_centre = 0.0;
    double worst = 0.0;
    for (const Eigen::Vector3d& p : made.scan.points) {
      if (!p.allFinite()) {
        continue;
      }
      const ClosestPoint foot = box.cad.closest(made.T_cad_scan * p);
      // The signed deviation of every point is the defect's displacement at its foot point.
      worst =
          std::max(worst, std::abs(foot.signed_distance - defectDisplacement(defect, foot.point)));
      const double lateral = (foot.point - defect.centre).norm();
      if (lateral < nearest) {
        nearest = lateral;
        at_centre = foot.signed_distance;
      }
    }
    std::printf(
        "depth %.1e: %zu points displaced, deviation %.4g m at %.2g m from the centre, "
        "worst departure from the cap %.3g m (σ 1e-5)\n",
        depth,
        made.counts.displaced,
        at_centre,
        nearest,
        worst);
    EXPECT_GT(made.counts.displaced, 100u);
    EXPECT_NEAR(at_centre, depth, 4e-5);  // 4 σ
    EXPECT_LT(worst, 6e-5);               // 6 σ over ~10^4 points
  }
}

TEST(VirtualScanner, SameScanWhateverTheThreadCount) {
  VirtualScannerConfig config = smallCamera(51);
  config.noise_ratio = 0.003;
  config.dropout_probability = 0.1;
  config.outlier_fraction = 0.02;
  SurfaceDefect defect;
  defect.centre = Eigen::Vector3d(0.0, 0.0, kSphereRadius);
  defect.radius = 0.02;
  defect.depth = -0.002;
  config.defects = {defect};
  SCOPED_TRACE("seed 51");
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const VirtualScan one = scan(sphere(), config);
  omp_set_num_threads(2);
  const VirtualScan two = scan(sphere(), config);
  omp_set_num_threads(threads);
  ASSERT_EQ(one.scan.points.size(), two.scan.points.size());
  EXPECT_EQ(std::memcmp(one.scan.points.data(),
                        two.scan.points.data(),
                        one.scan.points.size() * sizeof(Eigen::Vector3d)),
            0);
  EXPECT_EQ(one.pixels, two.pixels);
  EXPECT_TRUE(one.T_cad_scan.matrix() == two.T_cad_scan.matrix());
  config.seed = 52;
  const VirtualScan other = scan(sphere(), config);
  EXPECT_FALSE(other.T_cad_scan.matrix().isApprox(one.T_cad_scan.matrix()));
}

TEST(VirtualScanner, LineScannerProfilesAreParallelAndEvenlySpaced) {
  VirtualScannerConfig config = smallCamera(61);
  config.type = ScannerType::kLineScanner;
  config.height = 100;
  SCOPED_TRACE("seed 61");
  const VirtualScan made = scan(sphere(), config);
  // Automatic sweep: the fan's width at the part's centre, which sits on the axis.
  const double fan =
      2.0 * std::tan(0.5 * config.horizontal_fov_deg * kPi / 180.0) * made.working_distance;
  EXPECT_NEAR(made.sweep_length, fan, 1e-12);
  const double step = made.sweep_length / (config.height - 1);
  double worst_plane = 0.0;
  double worst_surface = 0.0;
  for (int row = 0; row < config.height; ++row) {
    for (int column = 0; column < config.width; ++column) {
      const Eigen::Vector3d& p =
          made.scan.points[static_cast<std::size_t>(row) * static_cast<std::size_t>(config.width) +
                           static_cast<std::size_t>(column)];
      if (p.allFinite()) {
        worst_plane =
            std::max(worst_plane, std::abs(p.y() - (row - 0.5 * (config.height - 1)) * step));
        worst_surface = std::max(worst_surface,
                                 std::abs(sphere().closest(made.T_cad_scan * p).signed_distance));
      }
    }
  }
  std::printf(
      "line scanner: %zu points, sweep %.4f m, worst off-profile %.3g m, off-surface "
      "%.3g m\n",
      made.counts.valid,
      made.sweep_length,
      worst_plane,
      worst_surface);
  EXPECT_GT(made.counts.valid, 1000u);
  EXPECT_LT(worst_plane, 1e-12);
  EXPECT_LT(worst_surface, 1e-9);
}

TEST(VirtualScanner, BadConfigsAreRejectedWithMessages) {
  const auto rejected = [](const VirtualScannerConfig& config, const std::string& field) {
    const std::vector<std::string> errors = validate(config);
    ASSERT_EQ(errors.size(), 1u) << field;
    EXPECT_NE(errors[0].find(field), std::string::npos) << errors[0];
    const VirtualScan made = makeVirtualScan(sphere(), config);
    EXPECT_EQ(made.status.code, StatusCode::kInvalidInput);
    EXPECT_NE(made.status.message.find(field), std::string::npos) << made.status.message;
    EXPECT_TRUE(made.scan.points.empty());
  };
  VirtualScannerConfig c;
  c.width = 1;
  rejected(c, "width");
  c = VirtualScannerConfig();
  c.horizontal_fov_deg = 180.0;
  rejected(c, "horizontal_fov_deg");
  c = VirtualScannerConfig();
  c.min_range = 2.0;
  c.max_range = 1.0;
  rejected(c, "min_range");
  c = VirtualScannerConfig();
  c.noise_sigma = -1e-3;
  rejected(c, "noise_sigma");
  c = VirtualScannerConfig();
  c.noise_sigma = 1e-3;
  c.noise_ratio = 1e-3;
  rejected(c, "not both");
  c = VirtualScannerConfig();
  c.dropout_probability = 1.5;
  rejected(c, "dropout_probability");
  c = VirtualScannerConfig();
  c.outlier_fraction = std::nan("");
  rejected(c, "outlier_fraction");
  c = VirtualScannerConfig();
  c.max_incidence_deg = 0.0;
  rejected(c, "max_incidence_deg");
  c = VirtualScannerConfig();
  c.fill_ratio = 0.0;
  rejected(c, "fill_ratio");
  c = VirtualScannerConfig();
  c.random_pose = false;
  c.T_sensor_cad.linear() = 2.0 * Eigen::Matrix3d::Identity();
  rejected(c, "T_sensor_cad");
  c = VirtualScannerConfig();
  c.defects.resize(2);
  c.defects[1].radius = 0.001;
  c.defects[1].depth = -0.001;
  rejected(c, "defects[0]");  // the default defect has radius 0
  c.defects[0] = c.defects[1];
  c.defects[1].depth = -0.002;  // deeper than a hemisphere
  rejected(c, "defects[1]");
  // Several problems: one message each.
  c = VirtualScannerConfig();
  c.width = 0;
  c.dropout_probability = -1.0;
  c.sweep_length = -1.0;
  EXPECT_EQ(validate(c).size(), 3u);
}

TEST(VirtualScanner, UnusableCadAndNothingInRangeAreReported) {
  const MeshQuery empty{TriangleMesh()};
  EXPECT_EQ(makeVirtualScan(empty, VirtualScannerConfig()).status.code, StatusCode::kInvalidInput);
  VirtualScannerConfig config = smallCamera(71);
  config.max_range = 0.1;  // the part sits farther away
  const VirtualScan made = makeVirtualScan(sphere(), config);
  EXPECT_EQ(made.status.code, StatusCode::kDegenerateInput) << made.status.message;
  EXPECT_GT(made.counts.out_of_range, 0u);
  EXPECT_FALSE(made.warnings.empty());
}

std::string temporaryPath(const std::string& name) {
  return ::testing::TempDir() + "virtual_scanner_test_" + std::to_string(::getpid()) + "_" + name;
}

TEST(VirtualScanner, OrganizedPcdKeepsTheGridAndTheNaNs) {
  VirtualScannerConfig config = smallCamera(81);
  config.noise_sigma = 1e-4;
  config.outlier_fraction = 0.01;
  const VirtualScan made = scan(sphere(), config);
  for (const bool binary : {true, false}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    const std::string path = temporaryPath(binary ? "binary.pcd" : "ascii.pcd");
    ASSERT_TRUE(saveScanPcd(path, made.scan, binary).ok());
    pcl::PCLPointCloud2 cloud;
    ASSERT_EQ(pcl::PCDReader().read(path, cloud), 0);
    EXPECT_EQ(cloud.width, 320u);
    EXPECT_EQ(cloud.height, 240u);
    EXPECT_FALSE(cloud.is_dense);
    // Our loader reads the whole grid back, NaN pixels in place (the pipeline removes them).
    const ScanLoadResult loaded = loadScan(path, 1.0);
    ASSERT_TRUE(loaded.status.ok()) << loaded.status.message;
    EXPECT_EQ(loaded.scan.width, 320);
    EXPECT_EQ(loaded.scan.height, 240);
    ASSERT_EQ(loaded.scan.points.size(), made.scan.points.size());
    EXPECT_EQ(loaded.non_finite_removed, 0u);
    for (std::size_t k = 0; k < made.scan.points.size(); ++k) {
      const Eigen::Vector3d& p = made.scan.points[k];
      if (p.allFinite()) {
        // float32 in the file: 6e-8 relative
        ASSERT_LT((loaded.scan.points[k] - p).norm(), 1e-7 * p.norm()) << "point " << k;
      } else {
        ASSERT_FALSE(loaded.scan.points[k].allFinite()) << "point " << k;
      }
    }
    std::remove(path.c_str());
  }
}

TEST(VirtualScanner, PcdWriterRefusesAGridThatDoesNotHoldThePoints) {
  Scan bad;
  bad.points.resize(5, Eigen::Vector3d::Zero());
  bad.width = 2;
  bad.height = 2;
  EXPECT_EQ(saveScanPcd(temporaryPath("bad.pcd"), bad).code, StatusCode::kInvalidInput);
  bad.width = 0;
  bad.height = 0;
  bad.normals.resize(4);
  EXPECT_EQ(saveScanPcd(temporaryPath("bad.pcd"), bad).code, StatusCode::kInvalidInput);
}

// Registration accuracy the scan must allow (issue 6): its truth is exact, so the pipeline's
// pose must match it as well as the pipeline can register a clean organized scan.
constexpr double kMaxRotationDeg = 0.5;
constexpr double kMaxCentroidRatio = 0.005;  // × L

const Model& blade() {
  static const std::shared_ptr<const Model> kModel = [] {
    const ModelLoadResult loaded =
        loadModel(std::string(FREEFORM_DATA_DIR) + "/blade/blade.stl", 0.001, "blade");
    EXPECT_TRUE(loaded.status.ok()) << loaded.status.message;
    return loaded.model;
  }();
  return *kModel;
}

struct BladeOutcome {
  RegistrationStatus registration = RegistrationStatus::kFailed;
  double rotation_deg = 0.0;
  double centroid_ratio = 0.0;  // × L
};

// One VGA scan of the blade at the seed's random pose, registered by the pipeline; with
// `table`, the blade rests on a table the camera sees around it.
BladeOutcome registerBladeScan(std::uint64_t seed,
                               bool table = false,
                               const PipelineConfig& pipeline = PipelineConfig()) {
  VirtualScannerConfig config;
  config.seed = seed;
  config.fill_ratio = 0.8;
  config.noise_ratio = 0.001;
  config.support = table;
  const VirtualScan made = scan(blade().query(), config);
  const InspectionResult result = inspect(blade(), made.scan, pipeline);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // of the blade's points
  for (std::size_t i = 0; i < made.scan.points.size(); ++i) {
    if (made.pixels[i] == PixelOutcome::kValid) {
      centroid += made.scan.points[i] / static_cast<double>(made.counts.valid);
    }
  }
  if (table) {
    std::printf("blade seed %lu on a table: %zu table points, %zu removed as support\n",
                static_cast<unsigned long>(seed),
                made.counts.support,
                result.counts.support_points);
  }
  BladeOutcome outcome;
  outcome.registration = result.registration;
  outcome.rotation_deg =
      Eigen::AngleAxisd(result.T_cad_scan.linear().transpose() * made.T_cad_scan.linear()).angle() *
      180.0 / kPi;
  outcome.centroid_ratio = (result.T_cad_scan * centroid - made.T_cad_scan * centroid).norm() /
                           blade().bounds().diagonal();
  std::printf(
      "blade seed %lu: %zu points (%zu grid faces), %s, rotation error %.4f°, centroid "
      "error %.5f L; %s\n",
      static_cast<unsigned long>(seed),
      made.counts.valid,
      result.counts.scan_faces,
      toString(result.registration),
      outcome.rotation_deg,
      outcome.centroid_ratio,
      result.status.message.c_str());
  EXPECT_GT(result.counts.scan_faces, 0u);  // the pipeline meshed the organized grid
  return outcome;
}

TEST(VirtualScanner, BladeScanRegistersAtRandomPoses) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const BladeOutcome outcome = registerBladeScan(seed);
    ASSERT_EQ(outcome.registration, RegistrationStatus::kOk);
    EXPECT_LT(outcome.rotation_deg, kMaxRotationDeg);
    EXPECT_LT(outcome.centroid_ratio, kMaxCentroidRatio);
  }
}

// Not every single view of the blade holds enough shape (edge-on views show a few thousand
// points of leading edge): the pipeline may fail such a view, but must not report a wrong pose
// as ok. Measured: seeds 4 and 9 (8.9k and 10.7k points of narrow view) fail with "no pose
// explains the scan"; the other five register.
TEST(VirtualScanner, BladeScanIsNeverRegisteredWrongly) {
  int registered = 0;
  for (std::uint64_t seed = 4; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const BladeOutcome outcome = registerBladeScan(seed);
    if (outcome.registration == RegistrationStatus::kOk) {
      ++registered;
      EXPECT_LT(outcome.rotation_deg, kMaxRotationDeg);
      EXPECT_LT(outcome.centroid_ratio, kMaxCentroidRatio);
    }
  }
  std::printf("blade seeds 4-10: %d of 7 registered\n", registered);
  EXPECT_GE(registered, 5);
}

// A camera sees the table under the part in more pixels than the part itself: the pipeline
// removes it as a support and registers the blade as well as without it; without the removal
// no pose explains the scan (measured: seeds 1-3 all `failed`, 0.05-0.10 of the scan explained;
// seed 1 is checked).
TEST(VirtualScanner, BladeOnATableRegistersOnceTheTableIsRemoved) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const BladeOutcome outcome = registerBladeScan(seed, true);
    ASSERT_EQ(outcome.registration, RegistrationStatus::kOk);
    EXPECT_LT(outcome.rotation_deg, kMaxRotationDeg);
    EXPECT_LT(outcome.centroid_ratio, kMaxCentroidRatio);
  }
  PipelineConfig keep_table;
  keep_table.support.remove = false;
  EXPECT_EQ(registerBladeScan(1, true, keep_table).registration, RegistrationStatus::kFailed);
}

TEST(VirtualScanner, SupportIsAPlaneBehindThePartThatLeavesThePartAsItWas) {
  VirtualScannerConfig config = smallCamera(21);
  config.noise_sigma = 1e-4;
  const VirtualScan alone = scan(sphere(), config);
  config.support = true;
  SCOPED_TRACE("seed 21");
  const VirtualScan on_table = scan(sphere(), config);
  const Eigen::Vector3d normal = on_table.support_plane.head<3>();
  const double offset = on_table.support_plane[3];
  ASSERT_NEAR(normal.norm(), 1.0, 1e-12);
  // Facing the sensor, tilted from the optical axis by at most support_tilt_deg.
  EXPECT_GE(-normal.z(), std::cos(config.support_tilt_deg * kPi / 180.0) - 1e-12);
  // The whole part on the sensor's side, touching the plane.
  double lowest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : sphere().mesh().vertices) {
    lowest = std::min(lowest, normal.dot(on_table.T_cad_scan.inverse() * v) - offset);
  }
  EXPECT_NEAR(lowest, 0.0, 1e-12);
  const VirtualScanCounts& c = on_table.counts;
  EXPECT_GT(c.support, c.valid);  // the table fills the rest of the image
  EXPECT_EQ(c.valid + c.outliers + c.support + c.misses + c.out_of_range + c.grazing + c.dropouts,
            on_table.scan.points.size());
  double worst_on_plane = 0.0;
  for (std::size_t i = 0; i < on_table.scan.points.size(); ++i) {
    const Eigen::Vector3d& p = on_table.scan.points[i];
    if (alone.pixels[i] == PixelOutcome::kValid) {
      // The part's pixels are the same, bit for bit: the support only fills the background.
      ASSERT_EQ(on_table.pixels[i], PixelOutcome::kValid) << "pixel " << i;
      ASSERT_EQ(p, alone.scan.points[i]) << "pixel " << i;
    } else if (on_table.pixels[i] == PixelOutcome::kSupport) {
      worst_on_plane = std::max(worst_on_plane, std::abs(normal.dot(p) - offset));
    }
  }
  // Range noise of σ along rays at most ~60° off the normal: within 5σ.
  std::printf("support: %zu points, farthest %.3g m off its plane (σ %.3g m)\n",
              c.support,
              worst_on_plane,
              config.noise_sigma);
  EXPECT_LT(worst_on_plane, 5.0 * config.noise_sigma);
}

}  // namespace
}  // namespace freeform_inspection
