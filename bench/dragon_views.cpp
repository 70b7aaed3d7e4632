// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "dragon_views.h"

#include <array>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>

#include "freeform_inspection/organized_mesh.h"

namespace freeform_inspection::bench {

bool readRangeScan(const std::string& path, RangeScan* scan, std::string* error) {
  std::ifstream in(path);
  std::string line;
  std::size_t vertices = 0;
  std::size_t cells = 0;
  while (std::getline(in, line) && line.rfind("end_header", 0) != 0) {
    std::istringstream words(line);
    std::string a, b, c;
    words >> a >> b >> c;
    if (a == "obj_info" && b == "num_cols") {
      scan->width = std::atoi(c.c_str());
    } else if (a == "obj_info" && b == "num_rows") {
      scan->height = std::atoi(c.c_str());
    } else if (a == "element" && b == "vertex") {
      vertices = std::strtoul(c.c_str(), nullptr, 10);
    } else if (a == "element" && b == "range_grid") {
      cells = std::strtoul(c.c_str(), nullptr, 10);
    }
  }
  if (!in || scan->width <= 0 || scan->height <= 0 ||
      cells != static_cast<std::size_t>(scan->width) * static_cast<std::size_t>(scan->height)) {
    *error = path + ": not a Cyberware range-grid PLY (num_cols × num_rows ≠ range_grid)";
    return false;
  }
  Points points(vertices);
  for (auto& p : points) {
    in >> p.x() >> p.y() >> p.z();
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  scan->grid.assign(cells, Eigen::Vector3d(nan, nan, nan));
  for (std::size_t cell = 0; cell < cells; ++cell) {
    int count = 0;
    in >> count;
    for (int k = 0; k < count; ++k) {
      std::size_t index = 0;
      in >> index;
      if (k == 0 && index < points.size()) {
        scan->grid[cell] = points[index];
      }
    }
  }
  if (!in) {
    *error = path + ": truncated";
    return false;
  }
  return true;
}

std::map<std::string, Eigen::Isometry3d> readDragonPoses(const std::string& conf_path) {
  std::map<std::string, Eigen::Isometry3d> poses;
  std::ifstream in(conf_path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string kind, file;
    double t[3], q[4];
    if (!(words >> kind >> file >> t[0] >> t[1] >> t[2] >> q[0] >> q[1] >> q[2] >> q[3]) ||
        kind != "bmesh") {
      continue;
    }
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).conjugate().toRotationMatrix();
    pose.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
    poses[file] = pose;
  }
  return poses;
}

std::vector<std::string> dragonViewNames() {
  std::vector<std::string> views;
  for (int degrees = 0; degrees < 360; degrees += 24) {
    views.push_back("dragonStandRight_" + std::to_string(degrees) + ".ply");
  }
  return views;
}

TriangleMesh viewAsMesh(const RangeScan& scan, const Eigen::Isometry3d& pose) {
  const Triangles grid_faces =
      triangulateOrganizedGrid(scan.grid, scan.width, scan.height, OrganizedMeshConfig());
  TriangleMesh mesh;
  std::vector<int> index(scan.grid.size(), -1);
  for (const auto& face : grid_faces) {
    std::array<int, 3> compact{};
    for (int c = 0; c < 3; ++c) {
      const auto g = static_cast<std::size_t>(face[c]);
      if (index[g] < 0) {
        index[g] = static_cast<int>(mesh.vertices.size());
        mesh.vertices.push_back(pose * scan.grid[g]);
      }
      compact[static_cast<std::size_t>(c)] = index[g];
    }
    mesh.faces.push_back({compact[0], compact[1], compact[2]});
  }
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& v : mesh.vertices) {
    centroid += v / static_cast<double>(mesh.vertices.size());
  }
  double outward = 0.0;
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(f[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(f[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(f[2])];
    outward += (b - a).cross(c - a).dot((a + b + c) / 3.0 - centroid);
  }
  if (outward < 0.0) {
    for (auto& f : mesh.faces) {
      std::swap(f[1], f[2]);
    }
  }
  return mesh;
}

Points measuredPoints(const RangeScan& scan) {
  Points points;
  for (const auto& p : scan.grid) {
    if (p.allFinite()) {
      points.push_back(p);
    }
  }
  return points;
}

bool readDragonPairs(const std::string& dir,
                     int step,
                     std::vector<DragonPair>* pairs,
                     std::string* error) {
  const auto poses = readDragonPoses(dir + "/dragonStandRight.conf");
  const std::vector<std::string> views = dragonViewNames();
  std::map<std::string, RangeScan> scans;
  for (const std::string& view : views) {
    if (poses.count(view) == 0) {
      *error = dir + "/dragonStandRight.conf: no pose of " + view;
      return false;
    }
    if (!readRangeScan(dir + "/" + view, &scans[view], error)) {
      return false;
    }
  }
  pairs->clear();
  const auto count = static_cast<int>(views.size());
  for (int v = 0; v < count; ++v) {
    DragonPair pair;
    pair.cad_view = views[static_cast<std::size_t>(v)];
    pair.scan_view = views[static_cast<std::size_t>(((v + step) % count + count) % count)];
    pair.cad = viewAsMesh(scans.at(pair.cad_view), poses.at(pair.cad_view));
    pair.scan = measuredPoints(scans.at(pair.scan_view));
    pair.T_cad_scan = poses.at(pair.scan_view);
    pairs->push_back(std::move(pair));
  }
  return true;
}

}  // namespace freeform_inspection::bench
