// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// generate_blade --out-dir DIR [--seed N]
//
// Writes the shipped sample part: DIR/blade.stl and DIR/blade_fine.stl (binary STL, millimetres),
// a synthetic scan DIR/blade_scan.ply (binary double PLY with normals, metres, moved by a random
// rigid transform) and DIR/blade_scan_T_cad_scan.txt (the 4x4 transform that undoes it, metres).
// Exit status 0 on success, 2 with one line on stderr on bad arguments or a write failure.
// The output is a pure function of the seed (default 42).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <system_error>
#include <vector>

#include "blade_geometry.h"
#include <Eigen/Geometry>

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace tools {
namespace {

constexpr int kExitFailure = 2;
constexpr std::uint32_t kDefaultSeed = 42;
constexpr std::size_t kScanPoints = 30000;
constexpr double kNoiseSigmaMm = 0.02;  // [mm] along the face normal
constexpr double kMetresPerMillimetre = 0.001;
constexpr double kScanTranslationM = 0.2;    // [m] length of the scan pose translation
constexpr double kMinScanRotationRad = 0.5;  // [rad] ~29 deg, so the pose is never near identity
constexpr double kPi = 3.14159265358979323846;
constexpr char kUsage[] = "usage: generate_blade --out-dir DIR [--seed N]";

struct Options {
  std::string out_dir;
  std::uint32_t seed = kDefaultSeed;
  bool help = false;
};

// The std:: distributions are implementation-defined, mt19937's raw output is not: converting
// it by hand keeps the shipped files reproducible with any standard library.
double uniform01(std::mt19937& rng) {
  const double high = static_cast<double>(rng() >> 5);    // 27 bits
  const double low = static_cast<double>(rng() >> 6);     // 26 bits
  return (high * 67108864.0 + low) / 9007199254740992.0;  // [0, 1) with 53 bits
}

// Box-Muller; 1 - u keeps the logarithm finite.
double gaussian(std::mt19937& rng) {
  const double radius = std::sqrt(-2.0 * std::log(1.0 - uniform01(rng)));
  return radius * std::cos(2.0 * kPi * uniform01(rng));
}

bool parseSeed(const std::string& text, std::uint32_t& seed) {
  if (text.empty() || text.size() > 10 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return false;
  }
  const unsigned long long value = std::stoull(text);
  seed = static_cast<std::uint32_t>(value);
  return value <= 0xffffffffULL;
}

// Returns an empty string on success, else the reason.
std::string parseArguments(int argc, char** argv, Options& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      options.help = true;
    } else if ((arg == "--out-dir" || arg == "--seed") && i + 1 >= argc) {
      return arg + " needs a value";
    } else if (arg == "--out-dir") {
      options.out_dir = argv[++i];
    } else if (arg == "--seed") {
      if (!parseSeed(argv[++i], options.seed)) {
        return std::string("--seed wants an integer in [0, 4294967295], got '") + argv[i] + "'";
      }
    } else {
      return "unknown argument '" + arg + "'";
    }
  }
  return options.out_dir.empty() && !options.help ? "--out-dir is required" : "";
}

// Uniformly random rotation (Shoemake's unit quaternion), redrawn while it is too close to the
// identity to test anything; translation of fixed length in a random direction.
Eigen::Isometry3d randomScanPose(std::mt19937& rng) {
  Eigen::Quaterniond q;
  do {
    const double u1 = uniform01(rng);
    const double u2 = 2.0 * kPi * uniform01(rng);
    const double u3 = 2.0 * kPi * uniform01(rng);
    q = Eigen::Quaterniond(std::sqrt(u1) * std::cos(u3),
                           std::sqrt(1.0 - u1) * std::sin(u2),
                           std::sqrt(1.0 - u1) * std::cos(u2),
                           std::sqrt(u1) * std::sin(u3));
  } while (Eigen::AngleAxisd(q).angle() < kMinScanRotationRad);
  Eigen::Vector3d direction;
  do {
    direction = Eigen::Vector3d(gaussian(rng), gaussian(rng), gaussian(rng));
  } while (direction.norm() < 1e-6);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.normalized().toRotationMatrix();
  pose.translation() = kScanTranslationM * direction.normalized();
  return pose;
}

std::vector<double> cumulativeAreas(const TriangleMesh& mesh) {
  std::vector<double> cumulative;
  cumulative.reserve(mesh.faces.size());
  double total = 0.0;
  for (const auto& f : mesh.faces) {
    total += triangleArea(mesh.vertices, f);
    cumulative.push_back(total);
  }
  return cumulative;
}

// Points uniform by area on the mesh (mm), displaced along the face normal by Gaussian noise.
Scan sampleSurface(const TriangleMesh& mesh, std::size_t count, std::mt19937& rng) {
  const std::vector<double> cumulative = cumulativeAreas(mesh);
  Scan scan;
  for (std::size_t i = 0; i < count; ++i) {
    const double pick = uniform01(rng) * cumulative.back();
    const auto face = static_cast<std::size_t>(
        std::upper_bound(cumulative.begin(), cumulative.end() - 1, pick) - cumulative.begin());
    const Eigen::Vector3i& f = mesh.faces[face];
    const double r1 = std::sqrt(uniform01(rng));
    const double r2 = uniform01(rng);
    const Eigen::Vector3d on_surface =
        (1.0 - r1) * mesh.vertices[static_cast<std::size_t>(f[0])] +
        r1 * (1.0 - r2) * mesh.vertices[static_cast<std::size_t>(f[1])] +
        r1 * r2 * mesh.vertices[static_cast<std::size_t>(f[2])];
    const Eigen::Vector3d& normal = mesh.face_normals[face];
    scan.points.push_back(on_surface + kNoiseSigmaMm * gaussian(rng) * normal);
    scan.normals.push_back(normal);
  }
  return scan;
}

// Millimetres in the CAD frame -> metres in the scan frame.
void moveToScanFrame(Scan& scan, const Eigen::Isometry3d& T_scan_cad) {
  for (auto& p : scan.points) {
    p = T_scan_cad * (kMetresPerMillimetre * p);
  }
  for (auto& n : scan.normals) {
    n = T_scan_cad.linear() * n;
  }
}

Status writeBlade(const std::string& path, const BladeParameters& parameters) {
  const TriangleMesh mesh = generateBlade(parameters);
  std::cout << path << ": " << mesh.vertices.size() << " vertices, " << mesh.faces.size()
            << " faces (mm)\n";
  return saveMeshStl(path, mesh, 1.0);  // the mesh is already in millimetres
}

Status writeScan(const std::string& out_dir, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const Eigen::Isometry3d T_scan_cad = randomScanPose(rng);
  Scan scan = sampleSurface(generateBlade(fineBladeParameters()), kScanPoints, rng);
  moveToScanFrame(scan, T_scan_cad);
  const std::string ply = out_dir + "/blade_scan.ply";
  std::cout << ply << ": " << scan.points.size() << " points (m)\n";
  const Status status =
      savePointsPly(ply, scan.points, scan.normals, PlyCoordinateType::kFloat64, true);
  if (!status.ok()) {
    return status;
  }
  return saveTransform(out_dir + "/blade_scan_T_cad_scan.txt", T_scan_cad.inverse().matrix());
}

int fail(const std::string& message) {
  std::cerr << "generate_blade: " << message << "\n";
  return kExitFailure;
}

int run(int argc, char** argv) {
  Options options;
  const std::string error = parseArguments(argc, argv, options);
  if (!error.empty()) {
    return fail(error + "; " + kUsage);
  }
  if (options.help) {
    std::cout << kUsage << "\n";
    return 0;
  }
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) {
    return fail("cannot create '" + options.out_dir + "': " + ec.message());
  }
  Status status = writeBlade(options.out_dir + "/blade.stl", BladeParameters());
  if (status.ok()) {
    status = writeBlade(options.out_dir + "/blade_fine.stl", fineBladeParameters());
  }
  if (status.ok()) {
    status = writeScan(options.out_dir, options.seed);
  }
  if (!status.ok()) {
    return fail(status.message);
  }
  return 0;
}

}  // namespace
}  // namespace tools
}  // namespace freeform_inspection

int main(int argc, char** argv) {
  return freeform_inspection::tools::run(argc, argv);
}
