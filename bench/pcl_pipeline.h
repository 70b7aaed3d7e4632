// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/types.h"

/// @file pcl_pipeline.h
/// PCL's standard feature-based registration (the alignment tutorial: voxel grid, normals, FPFH,
/// SampleConsensusPrerejective) followed by point-to-plane ICP, with every length relative to
/// the CAD's bounding-box diagonal L. The baseline of bench/pcl_compare; PCL types stay inside
/// pcl_pipeline.cpp so that only one file pays for PCL's headers.

namespace freeform_inspection {
namespace bench {

/// Parameters of the PCL pipeline. Lengths are in voxel-grid leaves, the leaf in L.
struct PclPipelineConfig {
  double leaf_ratio = 0.02;             ///< voxel-grid leaf, × L (both the CAD and the scan)
  double normal_radius = 2.0;           ///< NormalEstimationOMP radius, leaves
  double feature_radius = 5.0;          ///< FPFHEstimationOMP radius, leaves
  int max_iterations = 50000;           ///< SampleConsensusPrerejective iterations
  int samples = 3;                      ///< points per RANSAC hypothesis
  int correspondence_randomness = 5;    ///< k nearest features drawn from per sample
  float similarity_threshold = 0.9f;    ///< polygon edge-length similarity (prerejection)
  double max_correspondence = 2.5;      ///< SAC inlier distance, leaves
  float inlier_fraction = 0.25f;        ///< SAC accepts a pose explaining this share of the scan
  double icp_max_correspondence = 2.5;  ///< ICP pairing distance, leaves
  int icp_max_iterations = 50;          ///< ICP iterations
  /// dense CAD sample: points per leaf² of CAD surface (the ICP target and the input of the
  /// CAD's voxel grid), at least `cad_min_samples`, at most `cad_max_samples`
  double cad_samples_per_leaf2 = 25.0;
  std::size_t cad_min_samples = 100000;   ///< lower bound of the dense CAD sample
  std::size_t cad_max_samples = 1000000;  ///< upper bound of the dense CAD sample
  /// true: estimated normals are signed by the scan's own normals (when it has them) and by the
  /// CAD's face normals; false: on both sides away from the cloud's centroid (bare points)
  bool use_scan_normals = true;
};

/// Sizes and timings of the CAD side, computed once per part.
struct PclCadStats {
  std::size_t dense_points = 0;    ///< CAD surface sample (ICP target)
  std::size_t feature_points = 0;  ///< after the voxel grid and NaN-normal removal
  double seconds = 0.0;            ///< [s] sampling, voxel grid, normals, FPFH, kd-trees
};

/// What one PCL registration produced.
struct PclResult {
  bool converged = false;  ///< SampleConsensusPrerejective found a pose (ICP always runs after)
  Eigen::Isometry3d T_cad_scan = Eigen::Isometry3d::Identity();  ///< scan → CAD
  std::size_t scan_points = 0;     ///< full-resolution scan points (ICP source)
  std::size_t feature_points = 0;  ///< scan points after voxel grid and NaN-normal removal
  std::size_t sac_inliers = 0;     ///< inliers of the SAC pose
  std::vector<std::pair<std::string, double>> timings;  ///< [s] per stage, last "total"
};

/// The CAD side of the PCL pipeline, prepared once; align() registers one scan to it.
class PclRegistration {
 public:
  /// @brief Samples `mesh` (metres) uniformly by area, voxel-grids it, estimates normals
  /// (oriented outward by the face normals) and FPFH, and builds the kd-trees of the ICP target
  /// and of the features.
  PclRegistration(const TriangleMesh& mesh, const PclPipelineConfig& config);
  ~PclRegistration();
  PclRegistration(const PclRegistration&) = delete;
  PclRegistration& operator=(const PclRegistration&) = delete;

  /// Sizes and time of the preparation.
  const PclCadStats& cadStats() const;

  /// @brief Registers `scan` (metres, any pose) to the CAD: voxel grid, normals, FPFH, SAC,
  /// then point-to-plane ICP of the full-resolution scan onto the dense CAD sample.
  /// @param seed seeds std::rand, which SampleConsensusPrerejective draws its samples from.
  PclResult align(const Scan& scan, std::uint64_t seed);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bench
}  // namespace freeform_inspection
