// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// make_case --cad FILE [--cad-scale S] --out-scan OUT.ply --out-truth OUT.txt [--points N]
//           [--partial] [--noise R] [--outliers F] [--seed N]
//
// Writes one registration case for a CAD mesh (makeSyntheticScan): the scan as a binary double
// PLY with normals (metres, scan frame) and the truth T_cad_scan as four lines of four numbers
// (row-major, metres, like data/blade/blade_scan_T_cad_scan.txt). --noise and --outliers are
// ratios (σ × bounding-box diagonal, outliers × points). Exit status 0 on success, 2 with one
// line on stderr on bad arguments, an unusable mesh or a write failure.

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

#include "number_text.h"

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/synthetic_scan.h"

namespace freeform_inspection {
namespace tools {
namespace {

constexpr int kExitFailure = 2;
constexpr char kUsage[] =
    "usage: make_case --cad FILE [--cad-scale S] --out-scan OUT.ply --out-truth OUT.txt "
    "[--points N] [--partial] [--noise R] [--outliers F] [--seed N]";

struct Options {
  std::string cad;
  double cad_scale = 1.0;
  std::string out_scan;
  std::string out_truth;
  SyntheticScanConfig config;
  bool help = false;
};

// Returns an empty string on success, else the reason.
std::string parseArguments(int argc, char** argv, Options& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      options.help = true;
      continue;
    }
    if (arg == "--partial") {
      options.config.partial = true;
      continue;
    }
    const bool takes_value = arg == "--cad" || arg == "--out-scan" || arg == "--out-truth" ||
                             arg == "--cad-scale" || arg == "--noise" || arg == "--outliers" ||
                             arg == "--points" || arg == "--seed";
    if (!takes_value) {
      return "unknown argument '" + arg + "'";
    }
    if (i + 1 >= argc) {
      return arg + " needs a value";
    }
    const std::string value = argv[++i];
    std::uint64_t number = 0;
    bool ok = true;
    if (arg == "--cad") {
      options.cad = value;
    } else if (arg == "--out-scan") {
      options.out_scan = value;
    } else if (arg == "--out-truth") {
      options.out_truth = value;
    } else if (arg == "--cad-scale") {
      ok = parseDouble(value, options.cad_scale);
    } else if (arg == "--noise") {
      ok = parseDouble(value, options.config.noise_ratio);
    } else if (arg == "--outliers") {
      ok = parseDouble(value, options.config.outlier_fraction);
    } else if (arg == "--points") {
      ok = parseUnsigned(value, number) && number > 0;
      options.config.points = static_cast<std::size_t>(number);
    } else {  // --seed
      ok = parseUnsigned(value, number);
      options.config.seed = number;
    }
    if (!ok) {
      return "bad value '" + value + "' for " + arg;
    }
  }
  if (options.help) {
    return "";
  }
  if (options.cad.empty() || options.out_scan.empty() || options.out_truth.empty()) {
    return "--cad, --out-scan and --out-truth are required";
  }
  return "";
}

int fail(const std::string& message) {
  std::cerr << "make_case: " << message << "\n";
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
  const MeshLoadResult loaded = loadMesh(options.cad, options.cad_scale);
  if (!loaded.status.ok()) {
    return fail(loaded.status.message);
  }
  const MeshQuery cad(loaded.mesh);
  const SyntheticScan made = makeSyntheticScan(cad, options.config);
  if (!made.status.ok()) {
    return fail(made.status.message);
  }
  Status status = savePointsPly(
      options.out_scan, made.scan.points, made.scan.normals, PlyCoordinateType::kFloat64, true);
  if (status.ok()) {
    status = saveTransform(options.out_truth, made.T_cad_scan.matrix());
  }
  if (!status.ok()) {
    return fail(status.message);
  }
  std::cout << options.out_scan << ": " << made.scan.points.size() << " points (" << made.outliers
            << " outliers), truth in " << options.out_truth << "\n";
  return 0;
}

}  // namespace
}  // namespace tools
}  // namespace freeform_inspection

int main(int argc, char** argv) {
  return freeform_inspection::tools::run(argc, argv);
}
