// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// Registration success over generated cases (synthetic_scan.h): a CAD file, a noise level, full
// or partial views, outliers; prints one line per case and a summary, and with --json one JSON
// object per case for scripts. Success = rotation error < 2° and scan-centroid error < 1 % of L
// with status "ok"; a wrong pose reported as "ok" is counted separately (it must never happen).
//
//   registration_eval --cad FILE [--cad-scale S] [--noise R] [--partial] [--outliers F]
//                     [--points N] [--cases N] [--first-seed N] [--mesh-copy]
//                     [--camera [--table] [--edge-on DEG]] [--json] [--config YAML]
//                     [--scan-mesh FILE] [--guess DEG [--guess-shift F]]
//
// --mesh-copy is the paper's §4.5 experiment: the scan is the CAD mesh itself, vertices moved by
// Gaussian noise along their normals, at a random pose (a mesh scan, faces included).
// --camera registers one range image of the virtual scanner per case instead; --table puts the
// part on a table that the camera sees around it (the success rule's centroid is the part's
// points only); --edge-on DEG turns the part so that the optical axis lies within DEG of the
// plane of its two widest principal axes (a blade or a plate seen nearly edge-on: a narrow strip).
// --scan-mesh scans another mesh of the same part (same frame and units), e.g. a finer export:
// the scan then follows the curves the CAD's faces cut, as a real part's does (session 38).
// --guess DEG registers from a known pose instead of searching (inspectFrom, session 40): the
// truth turned by DEG about a random axis through the part's centre, moved by --guess-shift F × L.
// Environment: FI_KEEP_GRID keeps a camera view's grid, FI_NO_NORMALS drops the scan's normals,
// FI_VERBOSE prints every case's status message under its line, FI_DIAG how the pose relates to the
// truth (printTruthDiagnostics).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <string>

#include "pose_error.h"
#include <Eigen/Eigenvalues>

#include "freeform_inspection/config_yaml.h"
#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/pipeline.h"
#include "freeform_inspection/pose_uncertainty.h"
#include "freeform_inspection/synthetic_scan.h"
#include "freeform_inspection/virtual_scanner.h"

namespace fi = freeform_inspection;

namespace {

struct Options {
  std::string cad;
  double cad_scale = 1.0;
  fi::SyntheticScanConfig scan;
  int cases = 10;
  std::uint64_t first_seed = 1;
  bool json = false;
  bool mesh_copy = false;
  bool camera = false;        // --camera: one VGA range image (virtual_scanner.h) per case
  bool table = false;         // --table: the camera also sees the table the part rests on
  double edge_on_deg = -1.0;  // --edge-on: camera views within this of the part's plane; < 0 off
  std::string config;  // --config: a pipeline YAML (config/default.yaml's keys); default: none
  // --scan-mesh: scans are made of this mesh of the same part (same frame and units as the
  // CAD), e.g. a finer tessellation, so the CAD's chord error shows as it does on a real part.
  std::string scan_mesh;
  // --guess DEG: registers from a known pose (inspectFrom) instead of searching, the truth
  // turned by DEG about a random axis through the part's centre and moved by --guess-shift F
  // times L in a random direction (a fixture's nominal pose that far off); < 0 off.
  double guess_deg = -1.0;
  double guess_shift = 0.0;
};

// The truth turned by `deg` about a random axis through `centre` (CAD frame) and moved by
// `shift` [m] in a random direction: a known pose that far off, the same for a seed.
Eigen::Isometry3d guessNear(const Eigen::Isometry3d& truth,
                            const Eigen::Vector3d& centre,
                            double deg,
                            double shift,
                            std::uint64_t seed) {
  std::mt19937_64 rng(seed ^ 0x9e3779b97f4a7c15ULL);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Eigen::Vector3d axis = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
  const Eigen::Vector3d direction =
      Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
  Eigen::Isometry3d off = Eigen::Isometry3d::Identity();
  off.linear() = Eigen::AngleAxisd(deg * 3.14159265358979323846 / 180.0, axis).toRotationMatrix();
  off.translation() = centre - off.linear() * centre + shift * direction;
  return off * truth;
}

// Share of the scan's finite points within `reach` of the CAD at pose T.
double shareOnCad(const fi::Model& model,
                  const fi::Points& points,
                  const Eigen::Isometry3d& T,
                  double reach) {
  std::size_t near = 0;
  std::size_t finite = 0;
  for (const auto& p : points) {
    if (p.allFinite()) {
      ++finite;
      near += model.query().closest(T * p, reach).found ? 1 : 0;
    }
  }
  return static_cast<double>(near) / static_cast<double>(std::max<std::size_t>(finite, 1));
}

// FI_DIAG: how the reported pose relates to the truth. The share of the scan each explains
// within `reach`, the motion truth·result⁻¹, and every model symmetry S with how far S·result
// lands from the truth: a wrong pose whose twin is the truth shows as one row near 0°, 0 m.
// Then where the pipeline's own ICP lands when it starts at the truth (inspectFrom), measured
// like the success rule (turn, and the shift of the scan's centroid): a miss whose refinement
// from the truth also ends 2° or 1 % of L away is beyond the search's reach.
void printTruthDiagnostics(const fi::Model& model,
                           const fi::Scan& scan,
                           const Eigen::Isometry3d& truth,
                           const fi::InspectionResult& result,
                           const fi::PipelineConfig& config,
                           const Eigen::Vector3d& centroid,
                           double reach) {
  constexpr double kDeg = 180.0 / 3.14159265358979323846;
  const Eigen::Isometry3d& found = result.T_cad_scan;
  std::printf("    truth explains %.3f of the scan, the result %.3f (within %.3g m)\n",
              shareOnCad(model, scan.points, truth, reach),
              shareOnCad(model, scan.points, found, reach),
              reach);
  const Eigen::Isometry3d relative = truth * found.inverse();
  const Eigen::AngleAxisd turn(relative.linear());
  std::printf("    truth * result^-1: %.2f deg about (%.3f %.3f %.3f), t (%.4f %.4f %.4f) m\n",
              turn.angle() * kDeg,
              turn.axis().x(),
              turn.axis().y(),
              turn.axis().z(),
              relative.translation().x(),
              relative.translation().y(),
              relative.translation().z());
  for (const fi::Symmetry& symmetry : model.symmetries()) {
    const Eigen::Isometry3d twin = symmetry.S * found;
    std::printf("    symmetry (score %.3f): S * result is %.2f deg and %.4f m from the truth\n",
                symmetry.score,
                fi::bench::rotationErrorDeg(twin, truth),
                (twin.translation() - truth.translation()).norm());
  }
  for (const Eigen::Isometry3d& alternative : result.alternatives) {
    std::printf("    alternative: %.2f deg from the truth, explains %.3f\n",
                fi::bench::rotationErrorDeg(alternative, truth),
                shareOnCad(model, scan.points, alternative, reach));
  }
  const fi::InspectionResult from_truth = fi::inspectFrom(model, scan, truth, config);
  std::printf("    ICP from the truth: %s, %.2f deg and %.4f %%L from it\n",
              fi::toString(from_truth.registration),
              fi::bench::rotationErrorDeg(from_truth.T_cad_scan, truth),
              100.0 * (from_truth.T_cad_scan * centroid - truth * centroid).norm() /
                  model.bounds().diagonal());
}

// The CAD mesh with noise of σ along the area-weighted vertex normals, moved like `generated`.
fi::Scan noisyMeshCopy(const fi::TriangleMesh& mesh,
                       const fi::SyntheticScan& generated,
                       double sigma,
                       std::uint64_t seed) {
  fi::Points normals(mesh.vertices.size(), Eigen::Vector3d::Zero());
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d n = (mesh.vertices[static_cast<std::size_t>(f[1])] -
                               mesh.vertices[static_cast<std::size_t>(f[0])])
                                  .cross(mesh.vertices[static_cast<std::size_t>(f[2])] -
                                         mesh.vertices[static_cast<std::size_t>(f[0])]);
    for (int c = 0; c < 3; ++c) {
      normals[static_cast<std::size_t>(f[c])] += n;
    }
  }
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  const Eigen::Isometry3d T_scan_cad = generated.T_cad_scan.inverse();
  fi::Scan scan;
  scan.faces = mesh.faces;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Eigen::Vector3d n = normals[v].normalized();
    scan.points.push_back(T_scan_cad * (mesh.vertices[v] + noise(rng) * n));
  }
  return scan;
}

// --edge-on: the CAD → sensor pose of a camera looking along a direction within `tilt_deg` of
// the plane of the vertices' two widest principal axes (from either side, any roll: all from
// the seed), at the distance where the CAD's bounding sphere spans `fill` of the image's height
// (about the random pose's rule, virtual_scanner.h).
Eigen::Isometry3d edgeOnPose(const fi::TriangleMesh& mesh,
                             const fi::VirtualScannerConfig& camera,
                             double diagonal,
                             double tilt_deg,
                             std::uint64_t seed) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& v : mesh.vertices) {
    centre += v;
  }
  centre /= static_cast<double>(mesh.vertices.size());
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (const auto& v : mesh.vertices) {
    spread += (v - centre) * (v - centre).transpose();
  }
  const Eigen::Matrix3d axes =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(spread).eigenvectors();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const double tilt = (unit(rng) * 2.0 - 1.0) * tilt_deg * kDeg;  // from the plane
  const double azimuth = 360.0 * kDeg * unit(rng);
  const double roll = 360.0 * kDeg * unit(rng);
  const Eigen::Vector3d look =
      (std::sin(tilt) * axes.col(0) +
       std::cos(tilt) * (std::cos(azimuth) * axes.col(1) + std::sin(azimuth) * axes.col(2)))
          .normalized();
  const Eigen::Vector3d across = look.unitOrthogonal();
  const Eigen::Vector3d right = std::cos(roll) * across + std::sin(roll) * look.cross(across);
  Eigen::Matrix3d rotation;
  rotation.row(0) = right;
  rotation.row(1) = look.cross(right);
  rotation.row(2) = look;
  const double half_height = std::tan(0.5 * camera.horizontal_fov_deg * kDeg) *
                             static_cast<double>(camera.height) / static_cast<double>(camera.width);
  const double distance = diagonal / (camera.fill_ratio * 2.0 * half_height);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  pose.translation() = Eigen::Vector3d(0.0, 0.0, distance) - rotation * centre;
  return pose;
}

bool parse(int argc, char** argv, Options* options) {
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    const bool has_value = i + 1 < argc;
    if (flag == "--cad" && has_value) {
      options->cad = argv[++i];
    } else if (flag == "--cad-scale" && has_value) {
      options->cad_scale = std::atof(argv[++i]);
    } else if (flag == "--noise" && has_value) {
      options->scan.noise_ratio = std::atof(argv[++i]);
    } else if (flag == "--outliers" && has_value) {
      options->scan.outlier_fraction = std::atof(argv[++i]);
    } else if (flag == "--points" && has_value) {
      options->scan.points = static_cast<std::size_t>(std::atol(argv[++i]));
    } else if (flag == "--cases" && has_value) {
      options->cases = std::atoi(argv[++i]);
    } else if (flag == "--first-seed" && has_value) {
      options->first_seed = static_cast<std::uint64_t>(std::atol(argv[++i]));
    } else if (flag == "--partial") {
      options->scan.partial = true;
    } else if (flag == "--camera") {
      options->camera = true;
    } else if (flag == "--table") {
      options->table = true;
    } else if (flag == "--edge-on" && has_value) {
      options->edge_on_deg = std::atof(argv[++i]);
    } else if (flag == "--scan-mesh" && has_value) {
      options->scan_mesh = argv[++i];
    } else if (flag == "--mesh-copy") {
      options->mesh_copy = true;
    } else if (flag == "--guess" && has_value) {
      options->guess_deg = std::atof(argv[++i]);
    } else if (flag == "--guess-shift" && has_value) {
      options->guess_shift = std::atof(argv[++i]);
    } else if (flag == "--json") {
      options->json = true;
    } else if (flag == "--config" && i + 1 < argc) {
      options->config = argv[++i];
    } else {
      return false;
    }
  }
  return !options->cad.empty();
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!parse(argc, argv, &options)) {
    std::fprintf(stderr,
                 "usage: registration_eval --cad FILE [--cad-scale S] [--noise R] "
                 "[--partial] [--outliers F] [--points N] [--cases N] [--first-seed N] "
                 "[--mesh-copy] [--camera [--table] [--edge-on DEG]] [--json] [--config YAML] "
                 "[--scan-mesh FILE] [--guess DEG [--guess-shift F]]\n");
    return 2;
  }
  fi::PipelineConfig pipeline_config;
  if (!options.config.empty()) {
    const fi::ConfigLoadResult read = fi::loadPipelineConfigFile(options.config);
    if (!read.status.ok()) {
      std::fprintf(stderr, "registration_eval: %s\n", read.status.message.c_str());
      return 2;
    }
    pipeline_config = read.config;
  }
  const auto load_start = std::chrono::steady_clock::now();
  // The CAD's descriptors with the same settings as the scan's, as the CLI and the node do.
  const fi::ModelLoadResult loaded =
      fi::loadModel(options.cad, options.cad_scale, "eval", pipeline_config.descriptor);
  if (!loaded.status.ok()) {
    std::fprintf(stderr, "registration_eval: %s\n", loaded.status.message.c_str());
    return 2;
  }
  const fi::Model& model = *loaded.model;
  const double load_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
  const double diagonal = model.bounds().diagonal();
  std::unique_ptr<fi::MeshQuery> scanned_mesh;
  if (!options.scan_mesh.empty()) {
    const fi::MeshLoadResult other = fi::loadMesh(options.scan_mesh, options.cad_scale);
    if (!other.status.ok()) {
      std::fprintf(stderr, "registration_eval: %s\n", other.status.message.c_str());
      return 2;
    }
    scanned_mesh = std::make_unique<fi::MeshQuery>(other.mesh);
    std::printf("# scans of %s (%zu vertices); CAD chord error up to %.3g mm\n",
                options.scan_mesh.c_str(),
                other.mesh.vertices.size(),
                model.chordError().max * 1e3);
  }
  const fi::MeshQuery& scanned = scanned_mesh ? *scanned_mesh : model.query();
  std::printf("# %s: %zu vertices, L = %.4f m, %zu symmetries, model load %.2f s\n",
              options.cad.c_str(),
              model.mesh().vertices.size(),
              diagonal,
              model.symmetries().size(),
              load_s);
  int ok = 0, ambiguous = 0, failed = 0, success = 0, wrong_ok = 0;
  double total_time = 0.0;
  // Right poses' squared errors against the squared errors their covariance predicts.
  double rotation_sq = 0.0, rotation_predicted_sq = 0.0;
  double translation_sq = 0.0, translation_predicted_sq = 0.0;
  int calibrated = 0;
  for (int c = 0; c < options.cases; ++c) {
    fi::SyntheticScanConfig config = options.scan;
    config.seed = options.first_seed + static_cast<std::uint64_t>(c);
    const fi::SyntheticScan generated = fi::makeSyntheticScan(scanned, config);
    if (!generated.status.ok()) {
      std::fprintf(stderr, "registration_eval: %s\n", generated.status.message.c_str());
      return 2;
    }
    fi::Scan scan =
        options.mesh_copy
            ? noisyMeshCopy(model.mesh(), generated, config.noise_ratio * diagonal, config.seed)
            : generated.scan;
    Eigen::Isometry3d truth = generated.T_cad_scan;
    std::size_t outliers = options.mesh_copy ? 0 : generated.outliers;
    fi::Points part_points;  // camera: the measured points of the part (not of the table)
    if (options.camera) {
      fi::VirtualScannerConfig camera;
      camera.seed = config.seed;
      camera.fill_ratio = 0.8;
      camera.noise_ratio = config.noise_ratio;
      camera.support = options.table;
      if (options.edge_on_deg >= 0.0) {
        camera.random_pose = false;
        camera.T_sensor_cad =
            edgeOnPose(model.mesh(), camera, diagonal, options.edge_on_deg, config.seed);
      }
      const fi::VirtualScan view = fi::makeVirtualScan(scanned, camera);
      if (!view.status.ok()) {
        std::fprintf(stderr, "registration_eval: %s\n", view.status.message.c_str());
        return 2;
      }
      scan = fi::Scan();
      for (const auto& p : view.scan.points) {  // the measured points, in grid order
        if (p.allFinite()) {
          scan.points.push_back(p);
        }
      }
      if (std::getenv("FI_KEEP_GRID") != nullptr) {
        scan = view.scan;
      }
      truth = view.T_cad_scan;
      outliers = 0;
      for (std::size_t i = 0; i < view.scan.points.size(); ++i) {
        if (view.pixels[i] == fi::PixelOutcome::kValid) {
          part_points.push_back(view.scan.points[i]);
        }
      }
    }
    if (std::getenv("FI_NO_NORMALS") != nullptr) {
      scan.normals.clear();
    }
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    std::size_t surface = 0;
    const fi::Points& measured = options.camera ? part_points : scan.points;
    for (std::size_t i = 0; i + outliers < measured.size(); ++i) {
      if (measured[i].allFinite()) {
        centroid += measured[i];
        ++surface;
      }
    }
    centroid /= static_cast<double>(std::max<std::size_t>(surface, 1));
    const fi::InspectionResult result =
        options.guess_deg >= 0.0 ? fi::inspectFrom(model,
                                                   scan,
                                                   guessNear(truth,
                                                             truth * centroid,
                                                             options.guess_deg,
                                                             options.guess_shift * diagonal,
                                                             config.seed),
                                                   pipeline_config)
                                 : fi::inspect(model, scan, pipeline_config);
    const double rotation = fi::bench::rotationErrorDeg(result.T_cad_scan, truth);
    const double translation = (result.T_cad_scan * centroid - truth * centroid).norm() / diagonal;
    const bool right = rotation < 2.0 && translation < 0.01;
    const fi::PredictedSpread spread =
        fi::predictedSpread(result.pose_uncertainty, result.T_cad_scan, centroid);
    const double predicted_rotation_deg = spread.rotation * 180.0 / 3.14159265358979323846;
    if (right && result.pose_uncertainty.known) {
      ++calibrated;
      rotation_sq += rotation * rotation;
      rotation_predicted_sq += predicted_rotation_deg * predicted_rotation_deg;
      translation_sq += translation * translation;
      translation_predicted_sq += std::pow(spread.at_point / diagonal, 2);
    }
    const bool is_ok = result.registration == fi::RegistrationStatus::kOk;
    ok += is_ok ? 1 : 0;
    ambiguous += result.registration == fi::RegistrationStatus::kAmbiguous ? 1 : 0;
    failed += result.registration == fi::RegistrationStatus::kFailed ? 1 : 0;
    success += right && is_ok ? 1 : 0;
    wrong_ok += !right && is_ok ? 1 : 0;
    const double seconds = result.timings.back().seconds;
    total_time += seconds;
    const double rms_over_sigma =
        config.noise_ratio > 0.0 ? result.rmse / (config.noise_ratio * diagonal) : 0.0;
    if (options.json) {
      std::printf(
          "{\"seed\":%llu,\"status\":\"%s\",\"rotation_deg\":%.4f,\"translation_ratio\":%.6f,"
          "\"success\":%s,\"rmse_over_sigma\":%.3f,\"features\":%zu,\"candidates\":%zu,"
          "\"correspondences\":%zu,\"predicted_rotation_deg\":%.4f,"
          "\"predicted_translation_ratio\":%.6f,\"seconds\":%.4f}\n",
          static_cast<unsigned long long>(config.seed),
          fi::toString(result.registration),
          rotation,
          translation,
          right && is_ok ? "true" : "false",
          rms_over_sigma,
          result.counts.features,
          result.counts.candidates,
          result.counts.correspondences,
          predicted_rotation_deg,
          spread.at_point / diagonal,
          seconds);
    } else {
      std::printf(
          "seed %3llu %-9s rot %8.3f deg (±%.3f)  t %7.4f %%L (±%.4f)  rms/σ %5.2f  score %.3f  "
          "fit %.3f  surface %.3f  curve %.2f  f/c/k %zu/%zu/%zu  %.2f s%s\n",
          static_cast<unsigned long long>(config.seed),
          fi::toString(result.registration),
          rotation,
          predicted_rotation_deg,
          translation * 100.0,
          spread.at_point / diagonal * 100.0,
          rms_over_sigma,
          result.score,
          result.fitness,
          result.surface_on_cad,
          result.cad_curve_share,
          result.counts.features,
          result.counts.candidates,
          result.counts.correspondences,
          seconds,
          !right && is_ok ? "  <-- WRONG POSE REPORTED OK" : "");
      if (std::getenv("FI_DIAG") != nullptr) {
        printTruthDiagnostics(model,
                              scan,
                              truth,
                              result,
                              pipeline_config,
                              centroid,
                              3.0 * config.noise_ratio * diagonal);
      }
      if (std::getenv("FI_VERBOSE") != nullptr) {
        std::printf("    %s\n   ", result.status.message.c_str());
        for (const auto& timing : result.timings) {
          std::printf(" %s %.3f", timing.stage.c_str(), timing.seconds);
        }
        std::printf("\n");
      }
    }
  }
  if (calibrated > 0) {
    // The pose covariance's calibration: measured RMS errors of the right poses beside the RMS
    // their covariances predict (docs/registration.md, "Pose uncertainty").
    std::printf(
        "# right poses: rotation RMS %.4f deg (predicted %.4f), centroid RMS %.5f %%L "
        "(predicted %.5f)\n",
        std::sqrt(rotation_sq / calibrated),
        std::sqrt(rotation_predicted_sq / calibrated),
        100.0 * std::sqrt(translation_sq / calibrated),
        100.0 * std::sqrt(translation_predicted_sq / calibrated));
  }
  std::printf(
      "# success %d/%d, ok %d, ambiguous %d, failed %d, wrong-but-ok %d, "
      "mean %.2f s per scan\n",
      success,
      options.cases,
      ok,
      ambiguous,
      failed,
      wrong_ok,
      total_time / std::max(1, options.cases));
  return 0;
}
