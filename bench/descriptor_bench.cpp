// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// descriptor_bench: time and peak memory of the multiscale descriptors on the sample blade at a
// chosen size, as a mesh, as a cloud over the whole part, or as one unorganized view of it (what
// a scanner delivers), optionally with descriptor.coarse_ball_cells set. One JSON line per run;
// bench/run_descriptor_bench.sh runs the sizes of docs/benchmarks.md, one process each so peak
// memory belongs to one size. With FI_DESCRIPTOR_DUMP=FILE set it also writes the descriptors,
// normals and point cells as raw binary, so a change meant to leave them bit for bit as they were
// can be checked with `cmp` against the dump of the previous build.
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "blade_geometry.h"
#include <sys/resource.h>

#include "freeform_inspection/descriptor.h"
#include "freeform_inspection/mesh.h"
#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/surface_sampling.h"
#include "freeform_inspection/virtual_scanner.h"

namespace fi = freeform_inspection;

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The blade resampled to about `vertices` vertices, in metres.
fi::TriangleMesh bladeMesh(double vertices) {
  fi::tools::BladeParameters parameters;
  const double factor = std::sqrt(vertices / 7300.0);
  parameters.chord_stations = static_cast<int>(std::lround(parameters.chord_stations * factor));
  parameters.airfoil_intervals =
      static_cast<int>(std::lround(parameters.airfoil_intervals * factor));
  fi::TriangleMesh mesh = fi::tools::generateBlade(parameters);
  for (auto& v : mesh.vertices) {
    v *= 0.001;
  }
  mesh.face_normals = fi::computeFaceNormals(mesh.vertices, mesh.faces);
  return mesh;
}

// One view of the CAD by the virtual structured-light camera (random pose of seed 1, the part
// filling the image), its measured points kept as an unorganized cloud of about `points`: a
// first scan at VGA tells how many pixels see the part, the resolution is scaled to match.
fi::Points singleView(const fi::TriangleMesh& cad, double points) {
  const fi::MeshQuery query(cad);
  fi::VirtualScannerConfig config;  // noise-free, as the cloud mode's samples
  const fi::VirtualScan probe = fi::makeVirtualScan(query, config);
  const double scale =
      std::sqrt(points / static_cast<double>(std::max<std::size_t>(probe.counts.valid, 1)));
  config.width = static_cast<int>(std::lround(config.width * scale));
  config.height = static_cast<int>(std::lround(config.height * scale));
  fi::Points view;
  for (const auto& p : fi::makeVirtualScan(query, config).scan.points) {
    if (p.allFinite()) {
      view.push_back(p);
    }
  }
  return view;
}

long peakMemoryKiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

// Raw doubles of the descriptors (row-major by cell) and normals, then the point cells as ints.
void dumpDescriptors(const fi::DescriptorResult& result, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  const auto write = [&](const void* data, std::size_t bytes) {
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
  };
  for (Eigen::Index c = 0; c < result.cell_values.rows(); ++c) {
    for (Eigen::Index k = 0; k < result.cell_values.cols(); ++k) {
      const double v = result.cell_values(c, k);
      write(&v, sizeof v);
    }
  }
  for (const Eigen::Vector3d& n : result.curvature.normals) {
    write(n.data(), 3 * sizeof(double));
  }
  write(result.graph.point_cell.data(), result.graph.point_cell.size() * sizeof(int));
}

}  // namespace

int main(int argc, char** argv) {
  if ((argc != 3 && argc != 4) ||
      (std::string(argv[1]) != "mesh" && std::string(argv[1]) != "cloud" &&
       std::string(argv[1]) != "view")) {
    std::cerr << "usage: descriptor_bench mesh|cloud|view POINTS [COARSE_BALL_CELLS]\n";
    return 2;
  }
  const std::string mode = argv[1];
  const double size = std::atof(argv[2]);
  fi::DescriptorConfig config;
  if (argc == 4) {
    config.coarse_ball_cells = std::atof(argv[3]);
  }
  const fi::TriangleMesh cad = bladeMesh(7300);
  const auto radii = fi::kernelRadii(fi::computeBoundingBox(cad.vertices).diagonal(), config);
  fi::Points points;
  fi::Triangles faces;
  if (mode == "mesh") {
    fi::TriangleMesh mesh = bladeMesh(size);
    points = std::move(mesh.vertices);
    faces = std::move(mesh.faces);
  } else if (mode == "cloud") {
    points = fi::sampleSurface(cad, static_cast<std::size_t>(size), 1).points;
  } else {
    points = singleView(cad, size);
  }
  const long memory_before = peakMemoryKiB();
  const auto start = std::chrono::steady_clock::now();
  const fi::DescriptorResult result = fi::computeDescriptors(points, faces, {}, radii, config);
  const double seconds = secondsSince(start);
  std::cout << "{\"mode\": \"" << mode << "\", \"points\": " << points.size()
            << ", \"faces\": " << faces.size() << ", \"cells\": " << result.graph.size()
            << ", \"status\": \"" << fi::toString(result.status.code)
            << "\", \"seconds\": " << seconds << ", \"peak_rss_mib\": " << peakMemoryKiB() / 1024.0
            << ", \"rss_before_mib\": " << memory_before / 1024.0 << "}" << std::endl;
  if (const char* dump = std::getenv("FI_DESCRIPTOR_DUMP")) {
    dumpDescriptors(result, dump);
  }
  return result.status.ok() ? 0 : 1;
}
