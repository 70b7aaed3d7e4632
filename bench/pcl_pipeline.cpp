// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "pcl_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <utility>

#include <pcl/features/fpfh_omp.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/filters/filter.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/sample_consensus_prerejective.h>
#include <pcl/search/kdtree.h>

#include "freeform_inspection/mesh.h"
#include "freeform_inspection/surface_sampling.h"

namespace freeform_inspection {
namespace bench {
namespace {

using PointT = pcl::PointNormal;
using Cloud = pcl::PointCloud<PointT>;
using FeatureT = pcl::FPFHSignature33;
using Features = pcl::PointCloud<FeatureT>;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Points with their normals (zero where unknown) as a PCL cloud.
Cloud::Ptr toCloud(const Points& points, const Points& normals) {
  Cloud::Ptr cloud(new Cloud);
  cloud->reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    PointT p;
    p.getVector3fMap() = points[i].cast<float>();
    p.getNormalVector3fMap() = normals.size() == points.size()
                                   ? Eigen::Vector3f(normals[i].cast<float>())
                                   : Eigen::Vector3f::Zero();
    p.curvature = 0.0f;
    cloud->push_back(p);
  }
  return cloud;
}

// The downsampled cloud with estimated normals and its FPFH features, one per point.
struct Described {
  Cloud::Ptr points{new Cloud};
  Features::Ptr features{new Features};
  double voxel_s = 0.0;
  double normals_s = 0.0;
  double features_s = 0.0;
};

// The tutorial's preprocessing: voxel grid, NormalEstimationOMP, FPFHEstimationOMP. Estimated
// normals have no sign; FPFH depends on it, so both sides must agree on one. With `oriented`,
// each is flipped to agree with the input normals averaged over its voxel (the scanner's, or the
// CAD's face normals); otherwise away from the cloud's centroid, which needs no pose.
Described describe(const Cloud::ConstPtr& input,
                   double leaf,
                   const PclPipelineConfig& config,
                   bool oriented) {
  Described out;
  auto start = Clock::now();
  Cloud::Ptr down(new Cloud);
  pcl::VoxelGrid<PointT> grid;
  grid.setInputCloud(input);
  const auto leaf_f = static_cast<float>(leaf);
  grid.setLeafSize(leaf_f, leaf_f, leaf_f);
  grid.filter(*down);  // averages every field, the input normals included
  out.voxel_s = secondsSince(start);

  start = Clock::now();
  std::vector<Eigen::Vector3f> reference(down->size());
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  for (std::size_t i = 0; i < down->size(); ++i) {
    reference[i] = (*down)[i].getNormalVector3fMap();
    centroid += (*down)[i].getVector3fMap() / static_cast<float>(down->size());
  }
  pcl::NormalEstimationOMP<PointT, PointT> normals;
  normals.setInputCloud(down);
  normals.setRadiusSearch(config.normal_radius * leaf);
  normals.compute(*down);  // in place: writes normal_x/y/z and curvature only
  for (std::size_t i = 0; i < down->size(); ++i) {
    PointT& p = (*down)[i];
    const Eigen::Vector3f towards = oriented && reference[i].squaredNorm() > 0.0f
                                        ? reference[i]
                                        : p.getVector3fMap() - centroid;
    if (p.getNormalVector3fMap().dot(towards) < 0.0f) {
      p.getNormalVector3fMap() *= -1.0f;
    }
  }
  // Points with fewer than three neighbours (isolated outliers) have NaN normals.
  pcl::Indices kept;
  pcl::removeNaNNormalsFromPointCloud(*down, *out.points, kept);
  out.normals_s = secondsSince(start);

  start = Clock::now();
  pcl::FPFHEstimationOMP<PointT, PointT, FeatureT> fpfh;
  fpfh.setInputCloud(out.points);
  fpfh.setInputNormals(out.points);
  fpfh.setRadiusSearch(config.feature_radius * leaf);
  Features::Ptr features(new Features);
  fpfh.compute(*features);
  // A non-finite histogram would poison the feature kd-tree: drop it with its point.
  const Cloud::Ptr with_normals = out.points;
  out.points.reset(new Cloud);
  for (std::size_t i = 0; i < features->size(); ++i) {
    bool finite = true;
    for (const float v : (*features)[i].histogram) {
      finite = finite && std::isfinite(v);
    }
    if (finite) {
      out.points->push_back((*with_normals)[i]);
      out.features->push_back((*features)[i]);
    }
  }
  out.features_s = secondsSince(start);
  return out;
}

}  // namespace

struct PclRegistration::Impl {
  PclPipelineConfig config;
  double leaf = 0.0;
  PclCadStats stats;
  Cloud::Ptr dense;  // ICP target: the dense CAD sample with its face normals
  Described cad;
  pcl::search::KdTree<PointT>::Ptr dense_tree{new pcl::search::KdTree<PointT>};
  pcl::search::KdTree<PointT>::Ptr feature_points_tree{new pcl::search::KdTree<PointT>};
  // Kept across scans so the CAD-side trees are built once (as our Model keeps its structures).
  pcl::SampleConsensusPrerejective<PointT, PointT, FeatureT> sac;
  pcl::IterativeClosestPointWithNormals<PointT, PointT> icp;
};

PclRegistration::PclRegistration(const TriangleMesh& mesh, const PclPipelineConfig& config)
    : impl_(std::make_unique<Impl>()) {
  const auto start = Clock::now();
  Impl& d = *impl_;
  d.config = config;
  const double diagonal = computeBoundingBox(mesh.vertices).diagonal();
  d.leaf = config.leaf_ratio * diagonal;
  const double area = analyzeTopology(mesh).area;
  const auto wanted =
      static_cast<std::size_t>(config.cad_samples_per_leaf2 * area / (d.leaf * d.leaf));
  const std::size_t count =
      std::min(config.cad_max_samples, std::max(config.cad_min_samples, wanted));
  const SurfaceSample sample = sampleSurface(mesh, count, 7u);
  d.dense = toCloud(sample.points, sample.normals);
  d.cad = describe(d.dense, d.leaf, config, config.use_scan_normals);
  d.dense_tree->setInputCloud(d.dense);
  d.feature_points_tree->setInputCloud(d.cad.points);

  d.sac.setInputTarget(d.cad.points);
  d.sac.setSearchMethodTarget(d.feature_points_tree, true);
  d.sac.setTargetFeatures(d.cad.features);  // builds the feature kd-tree
  d.sac.setMaximumIterations(config.max_iterations);
  d.sac.setNumberOfSamples(config.samples);
  d.sac.setCorrespondenceRandomness(config.correspondence_randomness);
  d.sac.setSimilarityThreshold(config.similarity_threshold);
  d.sac.setMaxCorrespondenceDistance(config.max_correspondence * d.leaf);
  d.sac.setInlierFraction(config.inlier_fraction);

  d.icp.setInputTarget(d.dense);
  d.icp.setSearchMethodTarget(d.dense_tree, true);
  d.icp.setMaxCorrespondenceDistance(config.icp_max_correspondence * d.leaf);
  d.icp.setMaximumIterations(config.icp_max_iterations);
  // Stop like our ICP: the mean squared error changed by less than 1e-5 of itself, or the step
  // is negligible (1e-6 L, 1e-6 rad).
  d.icp.setEuclideanFitnessEpsilon(1e-5);
  d.icp.setTransformationEpsilon(std::pow(1e-6 * diagonal, 2));
  d.icp.setTransformationRotationEpsilon(std::cos(1e-6));

  d.stats.dense_points = d.dense->size();
  d.stats.feature_points = d.cad.points->size();
  d.stats.seconds = secondsSince(start);
}

PclRegistration::~PclRegistration() = default;

const PclCadStats& PclRegistration::cadStats() const {
  return impl_->stats;
}

PclResult PclRegistration::align(const Scan& scan, std::uint64_t seed) {
  Impl& d = *impl_;
  PclResult result;
  const auto start = Clock::now();
  const Cloud::Ptr full = toCloud(scan.points, scan.normals);
  result.scan_points = full->size();
  result.timings.emplace_back("convert", secondsSince(start));

  const Described described =
      describe(full, d.leaf, d.config, d.config.use_scan_normals && !scan.normals.empty());
  result.timings.emplace_back("voxel_grid", described.voxel_s);
  result.timings.emplace_back("normals", described.normals_s);
  result.timings.emplace_back("fpfh", described.features_s);
  result.feature_points = described.points->size();

  auto stage = Clock::now();
  std::srand(static_cast<unsigned>(seed));
  Cloud aligned;
  d.sac.setInputSource(described.points);
  d.sac.setSourceFeatures(described.features);
  d.sac.align(aligned);
  result.converged = d.sac.hasConverged();
  result.sac_inliers = d.sac.getInliers().size();
  const Eigen::Matrix4f coarse = d.sac.getFinalTransformation();
  result.timings.emplace_back("sac", secondsSince(stage));

  stage = Clock::now();
  d.icp.setInputSource(full);
  d.icp.align(aligned, coarse);
  result.T_cad_scan.matrix() = d.icp.getFinalTransformation().cast<double>();
  result.timings.emplace_back("icp", secondsSince(stage));
  result.timings.emplace_back("total", secondsSince(start));
  return result;
}

}  // namespace bench
}  // namespace freeform_inspection
