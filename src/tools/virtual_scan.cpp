// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// virtual_scan --cad FILE [--cad-scale S] --out SCAN.pcd|SCAN.ply [--truth T.txt] [--seed N]
//              [--width W] [--height H] [--fov DEG] [--min-range M] [--max-range M] [--fill F]
//              [--line-scanner] [--sweep M] [--noise SIGMA | --noise-ratio R] [--dropout P]
//              [--outliers F] [--max-incidence DEG] [--defect x,y,z,radius,depth]... [--table]
//
// Scans a CAD mesh with the virtual range sensor (virtual_scanner.h) at a random pose and writes
// the scan in the sensor frame, in metres: a .pcd keeps the organized grid (WIDTH × HEIGHT, NaN
// where nothing was measured), a .ply holds only the measured points (binary, double). --truth
// writes T_cad_scan as four lines of four numbers. Lengths are metres after --cad-scale; defect
// centres are in the CAD frame and are moved onto the closest point of the CAD surface. Exit
// status 0 on success, 2 with one line on stderr on bad arguments, an unusable mesh, a scan that
// measured nothing or a write failure. --table puts the part on a table that the sensor sees
// around it (VirtualScannerConfig::support).

#include <cctype>
#include <cstdint>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "number_text.h"

#include "freeform_inspection/io.h"
#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/virtual_scanner.h"

namespace freeform_inspection {
namespace tools {
namespace {

constexpr int kExitFailure = 2;
constexpr char kUsage[] =
    "usage: virtual_scan --cad FILE [--cad-scale S] --out SCAN.pcd|SCAN.ply [--truth T.txt] "
    "[--seed N] [--width W] [--height H] [--fov DEG] [--min-range M] [--max-range M] [--fill F] "
    "[--line-scanner] [--sweep M] [--noise SIGMA | --noise-ratio R] [--dropout P] [--outliers F] "
    "[--max-incidence DEG] [--defect x,y,z,radius,depth]... [--table]";

struct Options {
  std::string cad;
  double cad_scale = 1.0;
  std::string out;
  std::string truth;
  VirtualScannerConfig config;
  bool help = false;
};

bool parseInt(const std::string& text, int& value) {
  std::uint64_t number = 0;
  if (!parseUnsigned(text, number) || number > 1000000) {
    return false;
  }
  value = static_cast<int>(number);
  return true;
}

// "x,y,z,radius,depth", five numbers.
bool parseDefect(const std::string& text, SurfaceDefect& defect) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    double value = 0.0;
    if (!parseDouble(item, value)) {
      return false;
    }
    values.push_back(value);
  }
  if (values.size() != 5 || text.empty() || text.back() == ',') {
    return false;
  }
  defect.centre = Eigen::Vector3d(values[0], values[1], values[2]);
  defect.radius = values[3];
  defect.depth = values[4];
  return true;
}

using Setter = std::function<bool(const std::string&)>;

std::map<std::string, Setter> valueOptions(Options& o) {
  VirtualScannerConfig& c = o.config;
  const auto path = [](std::string& field) {
    return [&field](const std::string& v) {
      field = v;
      return !v.empty();
    };
  };
  const auto number = [](double& field) {
    return [&field](const std::string& v) { return parseDouble(v, field); };
  };
  const auto pixels = [](int& field) {
    return [&field](const std::string& v) { return parseInt(v, field); };
  };
  return {{"--cad", path(o.cad)},
          {"--out", path(o.out)},
          {"--truth", path(o.truth)},
          {"--cad-scale", number(o.cad_scale)},
          {"--seed", [&c](const std::string& v) { return parseUnsigned(v, c.seed); }},
          {"--width", pixels(c.width)},
          {"--height", pixels(c.height)},
          {"--fov", number(c.horizontal_fov_deg)},
          {"--min-range", number(c.min_range)},
          {"--max-range", number(c.max_range)},
          {"--fill", number(c.fill_ratio)},
          {"--sweep", number(c.sweep_length)},
          {"--noise", number(c.noise_sigma)},
          {"--noise-ratio", number(c.noise_ratio)},
          {"--dropout", number(c.dropout_probability)},
          {"--outliers", number(c.outlier_fraction)},
          {"--max-incidence", number(c.max_incidence_deg)},
          {"--defect", [&c](const std::string& v) {
             SurfaceDefect defect;
             c.defects.push_back(defect);
             return parseDefect(v, c.defects.back());
           }}};
}

bool endsWith(const std::string& text, const std::string& suffix) {
  if (text.size() < suffix.size()) {
    return false;
  }
  std::string tail = text.substr(text.size() - suffix.size());
  for (char& ch : tail) {
    ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  }
  return tail == suffix;
}

// Returns an empty string on success, else the reason.
std::string parseArguments(int argc, char** argv, Options& options) {
  const std::map<std::string, Setter> setters = valueOptions(options);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      options.help = true;
      continue;
    }
    if (arg == "--line-scanner") {
      options.config.type = ScannerType::kLineScanner;
      continue;
    }
    if (arg == "--table") {
      options.config.support = true;
      continue;
    }
    const auto setter = setters.find(arg);
    if (setter == setters.end()) {
      return "unknown argument '" + arg + "'";
    }
    if (i + 1 >= argc) {
      return arg + " needs a value";
    }
    const std::string value = argv[++i];
    if (!setter->second(value)) {
      return "bad value '" + value + "' for " + arg;
    }
  }
  if (options.help) {
    return "";
  }
  if (options.cad.empty() || options.out.empty()) {
    return "--cad and --out are required";
  }
  if (!endsWith(options.out, ".pcd") && !endsWith(options.out, ".ply")) {
    return "--out '" + options.out + "' must end in .pcd (organized) or .ply";
  }
  const std::vector<std::string> problems = validate(options.config);
  return problems.empty() ? "" : joinMessages(problems);
}

int fail(const std::string& message) {
  std::cerr << "virtual_scan: " << message << "\n";
  return kExitFailure;
}

// Defect centres onto the surface: the cap is measured from its centre in 3-D, so a centre off
// the surface would make a shallower defect than asked for.
void snapDefects(const MeshQuery& cad, std::vector<SurfaceDefect>& defects) {
  for (SurfaceDefect& defect : defects) {
    const ClosestPoint closest = cad.closest(defect.centre);
    if (closest.found) {
      defect.centre = closest.point;
    }
  }
}

Status save(const Options& options, const VirtualScan& made) {
  Status status;
  if (endsWith(options.out, ".pcd")) {
    status = saveScanPcd(options.out, made.scan, true);
  } else {
    Points measured;
    for (const Eigen::Vector3d& p : made.scan.points) {
      if (p.allFinite()) {
        measured.push_back(p);
      }
    }
    status = savePointsPly(options.out, measured, {}, PlyCoordinateType::kFloat64, true);
  }
  if (status.ok() && !options.truth.empty()) {
    status = saveTransform(options.truth, made.T_cad_scan.matrix());
  }
  return status;
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
  snapDefects(cad, options.config.defects);
  const VirtualScan made = makeVirtualScan(cad, options.config);
  if (!made.status.ok()) {
    return fail(made.status.message);
  }
  const Status status = save(options, made);
  if (!status.ok()) {
    return fail(status.message);
  }
  for (const std::string& warning : made.warnings) {
    std::cerr << "virtual_scan: warning: " << warning << "\n";
  }
  std::cout << options.out << ": " << made.scan.width << " x " << made.scan.height << " pixels, "
            << made.counts.valid << " measured points (" << made.counts.displaced
            << " on defects), " << made.counts.outliers << " outliers; working distance "
            << made.working_distance << " m"
            << (options.truth.empty() ? "" : "; truth in " + options.truth) << "\n";
  return 0;
}

}  // namespace
}  // namespace tools
}  // namespace freeform_inspection

int main(int argc, char** argv) {
  return freeform_inspection::tools::run(argc, argv);
}
