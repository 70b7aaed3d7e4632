// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// deviation_bench: time of the inspection after the registration — signed distance to the CAD,
// statistics, coverage, shape-free defect clustering — for N scan points on the shipped blade
// (points sampled on its surface with noise σ along the normals, already in the CAD frame).
//   deviation_bench --cad data/blade/blade.stl --points 100000 [--sigma 2e-5]
// (a σ above the ±0.1 mm band puts most points out of tolerance: the defect clustering's worst
// case).
// One JSON line: seconds per part and peak resident memory.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <sys/resource.h>

#include "freeform_inspection/defects.h"
#include "freeform_inspection/deviation.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/surface_sampling.h"

namespace fi = freeform_inspection;

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::string cad;
  std::size_t points = 100000;
  double sigma = 2e-5;  // [m] noise along the normals
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--cad") {
      cad = argv[i + 1];
    } else if (flag == "--sigma") {
      sigma = std::atof(argv[i + 1]);
    } else if (flag == "--points") {
      points = static_cast<std::size_t>(std::atol(argv[i + 1]));
    }
  }
  if (cad.empty() || points == 0) {
    std::fprintf(stderr, "usage: deviation_bench --cad BLADE.stl (mm) [--points N] [--sigma M]\n");
    return 2;
  }
  const fi::ModelLoadResult loaded = fi::loadModel(cad, 0.001, "bench");
  if (!loaded.status.ok()) {
    std::fprintf(stderr, "deviation_bench: %s\n", loaded.status.message.c_str());
    return 2;
  }
  const fi::Model& model = *loaded.model;
  const fi::SurfaceSample scan = fi::sampleSurface(model.mesh(), points, 7, sigma);
  fi::ToleranceConfig tolerance;
  fi::DeviationConfig config;

  auto start = std::chrono::steady_clock::now();
  const fi::SurfaceDistances distances = fi::measureDeviation(
      model, scan.points, config.max_distance_ratio * model.bounds().diagonal());
  const double distance_s = secondsSince(start);
  start = std::chrono::steady_clock::now();
  const fi::DeviationStatistics stats =
      fi::summarizeDeviation(distances.deviation, tolerance, config.histogram_bins);
  const double statistics_s = secondsSince(start);
  start = std::chrono::steady_clock::now();
  const double coverage =
      fi::surfaceCoverage(model, scan.points, config.coverage_distance_cells * model.cellSize());
  const double coverage_s = secondsSince(start);
  start = std::chrono::steady_clock::now();
  const fi::DefectResult defects =
      fi::findDefects(scan.points, {}, distances.deviation, tolerance, fi::DefectConfig());
  const double defects_s = secondsSince(start);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf(
      "{\"points\":%zu,\"distance_s\":%.4f,\"statistics_s\":%.4f,\"coverage_s\":%.4f,"
      "\"defects_s\":%.4f,\"total_s\":%.4f,\"rms_m\":%.3g,\"coverage\":%.4f,\"defects\":%zu,"
      "\"peak_rss_mb\":%.1f}\n",
      points,
      distance_s,
      statistics_s,
      coverage_s,
      defects_s,
      distance_s + statistics_s + coverage_s + defects_s,
      stats.rms,
      coverage,
      defects.regions.size(),
      static_cast<double>(usage.ru_maxrss) / 1024.0);
  return 0;
}
