// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>
#include <vector>

#include <ros/node_handle.h>

#include "freeform_inspection/pipeline.h"

namespace freeform_inspection_ros {

/// Node-level settings (the pipeline's own settings are in `pipeline`).
struct NodeConfig {
  std::string model;                 ///< CAD file path or package:// URL; empty = none at start
  std::string model_units;           ///< "m", "mm" or "in"; required when `model` is set
  std::string model_id = "default";  ///< name of the start-up model in Inspect requests
  std::string part_frame = "part";   ///< tf child frame of the part pose and of the CAD marker
  bool publish_tf = true;            ///< broadcast the part pose when the registration is ok
  /// Send the pose on /tf_static (latched: it holds until the next inspection, and viewers that
  /// start later see it) instead of once on /tf.
  bool tf_static = false;
  bool auto_inspect = false;   ///< inspect every scan arriving on `scan` (latest wins)
  int viz_max_points = 20000;  ///< ~deviation_viz carries at most this many points
  /// Frame that parents the reported part pose: the scan is inspected in its own frame and the
  /// pose carried into this one through tf2 at the scan's stamp; empty: the scan's frame.
  std::string fixed_frame;
  double tf_timeout = 0.5;  ///< [s] how long to wait for the scan's transform
  /// Directories ~load_model may read from; empty: the start-up model's directory only.
  std::vector<std::string> model_dirs;
  int max_model_mb = 500;  ///< ~load_model refuses larger CAD files [MiB]
  /// Each inspection's HTML report and deviation PLY are written here; empty: none are.
  std::string report_dir;
  /// The models' descriptors and symmetries are kept here between loads (model_cache.h), so a
  /// restart or a changeover back to a known part skips computing them; empty: no cache.
  /// Default: $ROS_HOME/freeform_inspection/model_cache (ROS_HOME defaults to ~/.ros).
  std::string model_cache_dir;
  /// Named regions of the CAD with their own tolerance or left out of the verdict (regions.h):
  /// a YAML file path or package:// URL, read at start-up into pipeline.regions; empty: none.
  std::string regions_file;
  /// Comparison points of the CAD (comparison_points.h): a YAML file path or package:// URL,
  /// read at start-up into pipeline.comparison_points; empty: none.
  std::string points_file;
  freeform_inspection::PipelineConfig pipeline;  ///< ~input/*, ~tolerance/*
};

/// Parameters read once at start-up.
struct NodeConfigResult {
  NodeConfig config;
  std::vector<std::string> errors;    ///< fatal: the node refuses to start
  std::vector<std::string> warnings;  ///< e.g. unknown private parameters (likely misspelt)
};

/// @brief The only parameter reader: every private parameter, once, validated.
NodeConfigResult loadNodeConfig(const ros::NodeHandle& pnh);

/// @brief Resolves "package://pkg/path" and "file:///path" to a file path; other text is
/// returned unchanged. An unknown package resolves to "".
std::string resolveModelPath(const std::string& uri);

}  // namespace freeform_inspection_ros
