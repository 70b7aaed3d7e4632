// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

/// @file pcl_compare_report.h
/// What bench/pcl_compare measured and how it is printed: one record per method and case, the
/// markdown tables of docs/benchmarks.md and the JSON for scripts (bench/plot_scaling.py).

namespace freeform_inspection {
namespace bench {

/// One registration of one case by one method.
struct CaseRecord {
  std::string part;    ///< CAD file name
  std::string set;     ///< case-set label, e.g. "partial 1%"; "scaling" in the scaling run
  std::string method;  ///< "ours" | "pcl"
  std::uint64_t seed = 0;
  std::size_t points = 0;  ///< scan points handed to the method (outliers included)
  /// ours: "ok" | "ambiguous" | "failed"; pcl: "converged" | "not_converged" (SAC's verdict)
  std::string status;
  std::string message;   ///< ours: why it stopped, when it did
  bool claimed = false;  ///< the method vouches for its pose: ours "ok", PCL SAC converged
  bool right = false;    ///< rotation error < 2° and centroid error < 1 % of L
  bool success = false;  ///< right, and for ours also "ok"
  double rotation_deg = 0.0;
  double translation_ratio = 0.0;     ///< centroid error / L
  double rms_over_sigma = 0.0;        ///< RMS distance of the true surface points to the CAD / σ
  double truth_rms_over_sigma = 0.0;  ///< the same at the true pose (the floor)
  double seconds = 0.0;               ///< [s] registration: scan in, pose out
  double seconds_total =
      0.0;                 ///< [s] ours: the whole inspect() (deviation included); pcl: = seconds
  double peak_mib = -1.0;  ///< resident-memory growth during the call; < 0 unknown
  std::vector<std::pair<std::string, double>> timings;  ///< [s] per stage as the method reports
};

/// The once-per-part preparation of both methods.
struct PartRecord {
  std::string part;  ///< CAD file name
  std::size_t vertices = 0;
  double diagonal = 0.0;        ///< [m] L
  double ours_seconds = -1.0;   ///< loadModel (file read, descriptors, symmetries); < 0 not run
  double ours_peak_mib = -1.0;  ///< resident growth of loadModel
  double pcl_seconds = -1.0;    ///< CAD sampling, voxel grid, normals, FPFH, kd-trees
  double pcl_peak_mib = -1.0;   ///< resident growth of that
  std::size_t pcl_dense_points = 0;    ///< ICP target
  std::size_t pcl_feature_points = 0;  ///< CAD points with FPFH features
};

/// How the run was made, for the JSON and the table's header.
struct RunInfo {
  std::string command;        ///< the command line
  std::string cpu;            ///< model name from /proc/cpuinfo
  unsigned threads = 0;       ///< hardware threads
  std::string memory_method;  ///< how peak_mib was measured
  int cases = 0;              ///< cases per part and set
  bool scan_normals = true;   ///< the scans carried their normals
  bool scaling = false;       ///< a scaling run: one set per scan size
};

/// @brief Markdown on stdout: per set and method (success, times, errors, memory), the time
/// ratio, per part and set the successes, the preparation per part.
/// @param set_order the set labels in the order to print.
void printCaseTables(const std::vector<CaseRecord>& records,
                     const std::vector<PartRecord>& parts,
                     const std::vector<std::string>& set_order,
                     const RunInfo& info);

/// @brief Markdown on stdout: per scan size, the median stage times of ours and PCL's.
void printScalingTable(const std::vector<CaseRecord>& records);

/// @brief Writes everything as one JSON object: `run`, `parts`, `cases`, `summary` (per set and
/// method, the numbers of the table) and `scaling` (per size and method, median stage times).
/// @return false when the file cannot be written.
bool writeJson(const std::string& path,
               const std::vector<CaseRecord>& records,
               const std::vector<PartRecord>& parts,
               const std::vector<std::string>& set_order,
               const RunInfo& info);

}  // namespace bench
}  // namespace freeform_inspection
