// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "parameters.h"

#include <cstdlib>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <ros/package.h>
#include <ros/param.h>

#include "freeform_inspection/config_fields.h"
#include "freeform_inspection/model.h"

namespace freeform_inspection_ros {
namespace {

namespace fi = freeform_inspection;

const std::vector<std::string> kNodeKeys = {"model",
                                            "model_units",
                                            "model_id",
                                            "part_frame",
                                            "publish_tf",
                                            "tf_static",
                                            "auto_inspect",
                                            "viz_max_points",
                                            "model_dirs",
                                            "fixed_frame",
                                            "tf_timeout",
                                            "max_model_mb",
                                            "report_dir",
                                            "model_cache_dir",
                                            "regions_file",
                                            "points_file"};

struct ReadParam {
  const ros::NodeHandle& pnh;
  const std::string& key;
  std::vector<std::string>* errors;

  void operator()(double* target) const { pnh.param(key, *target, *target); }
  void operator()(bool* target) const { pnh.param(key, *target, *target); }
  void operator()(int* target) const { pnh.param(key, *target, *target); }
  void operator()(std::vector<double>* target) const {
    // A list of numbers (integers are taken as numbers too: [0, 0, 0, 1, 1, 1] is a valid box).
    XmlRpc::XmlRpcValue list;
    if (!pnh.getParam(key, list)) {
      return;
    }
    if (list.getType() != XmlRpc::XmlRpcValue::TypeArray) {
      errors->push_back("~" + key + " must be a list of numbers");
      return;
    }
    std::vector<double> values;
    for (int i = 0; i < list.size(); ++i) {
      if (list[i].getType() == XmlRpc::XmlRpcValue::TypeDouble) {
        values.push_back(static_cast<double>(list[i]));
      } else if (list[i].getType() == XmlRpc::XmlRpcValue::TypeInt) {
        values.push_back(static_cast<int>(list[i]));
      } else {
        errors->push_back("~" + key + " must be a list of numbers");
        return;
      }
    }
    *target = std::move(values);
  }
  void operator()(std::size_t* target) const {
    int value = static_cast<int>(*target);
    pnh.param(key, value, value);
    if (value < 0) {
      errors->push_back("~" + key + " must not be negative");
      return;
    }
    *target = static_cast<std::size_t>(value);
  }
};

void warnUnknownKeys(const ros::NodeHandle& pnh,
                     const std::set<std::string>& known,
                     std::vector<std::string>* warnings) {
  std::vector<std::string> names;
  ros::param::getParamNames(names);
  const std::string prefix = pnh.getNamespace() + "/";
  for (const auto& name : names) {
    if (name.rfind(prefix, 0) == 0 && known.count(name.substr(prefix.size())) == 0) {
      warnings->push_back("unknown parameter '" + name + "' is ignored (misspelt?)");
    }
  }
}

// $ROS_HOME/freeform_inspection/model_cache, ROS_HOME being ~/.ros unless set; empty without
// either variable.
std::string defaultModelCacheDir() {
  const char* ros_home = std::getenv("ROS_HOME");
  if (ros_home != nullptr && ros_home[0] != '\0') {
    return std::string(ros_home) + "/freeform_inspection/model_cache";
  }
  const char* home = std::getenv("HOME");
  if (home != nullptr && home[0] != '\0') {
    return std::string(home) + "/.ros/freeform_inspection/model_cache";
  }
  return "";
}

}  // namespace

NodeConfigResult loadNodeConfig(const ros::NodeHandle& pnh) {
  NodeConfigResult result;
  NodeConfig& config = result.config;
  pnh.param("model", config.model, config.model);
  pnh.param("model_units", config.model_units, config.model_units);
  pnh.param("model_id", config.model_id, config.model_id);
  pnh.param("part_frame", config.part_frame, config.part_frame);
  pnh.param("publish_tf", config.publish_tf, config.publish_tf);
  pnh.param("tf_static", config.tf_static, config.tf_static);
  pnh.param("auto_inspect", config.auto_inspect, config.auto_inspect);
  pnh.param("viz_max_points", config.viz_max_points, config.viz_max_points);
  pnh.param("model_dirs", config.model_dirs, config.model_dirs);
  pnh.param("fixed_frame", config.fixed_frame, config.fixed_frame);
  pnh.param("tf_timeout", config.tf_timeout, config.tf_timeout);
  pnh.param("max_model_mb", config.max_model_mb, config.max_model_mb);
  pnh.param("report_dir", config.report_dir, config.report_dir);
  pnh.param("model_cache_dir", config.model_cache_dir, defaultModelCacheDir());
  pnh.param("regions_file", config.regions_file, config.regions_file);
  pnh.param("points_file", config.points_file, config.points_file);
  std::set<std::string> known(kNodeKeys.begin(), kNodeKeys.end());
  for (const auto& field : fi::configFields(config.pipeline)) {
    std::visit(ReadParam{pnh, field.key, &result.errors}, field.target);
    known.insert(field.key);
  }
  if (!config.model.empty() && !fi::unitScale(config.model_units)) {
    result.errors.push_back("~model_units must be 'm', 'mm' or 'in' (got '" + config.model_units +
                            "'): CAD units are never guessed");
  }
  if (!(config.tf_timeout >= 0.0 && config.tf_timeout <= 60.0)) {
    result.errors.push_back("~tf_timeout must be in [0, 60] s (got " +
                            std::to_string(config.tf_timeout) + ")");
  }
  if (config.max_model_mb < 1) {
    result.errors.push_back("~max_model_mb must be at least 1 (got " +
                            std::to_string(config.max_model_mb) + ")");
  }
  if (config.viz_max_points < 1) {
    result.errors.push_back("~viz_max_points must be at least 1 (got " +
                            std::to_string(config.viz_max_points) + ")");
  }
  if (config.part_frame.empty()) {
    result.errors.push_back("~part_frame must not be empty");
  }
  if (!config.regions_file.empty()) {
    fi::RegionsLoadResult regions = fi::loadRegionsFile(resolveModelPath(config.regions_file));
    if (regions.status.ok()) {
      config.pipeline.regions = std::move(regions.regions);
    } else {
      result.errors.push_back("~regions_file: " + regions.status.message);
    }
  }
  if (!config.points_file.empty()) {
    fi::ComparisonPointsLoadResult points =
        fi::loadComparisonPointsFile(resolveModelPath(config.points_file));
    if (points.status.ok()) {
      config.pipeline.comparison_points = std::move(points.points);
      config.pipeline.datum_precedence = std::move(points.datum_precedence);
    } else {
      result.errors.push_back("~points_file: " + points.status.message);
    }
  }
  for (const auto& error : fi::validate(config.pipeline)) {
    result.errors.push_back(error);
  }
  warnUnknownKeys(pnh, known, &result.warnings);
  return result;
}

std::string resolveModelPath(const std::string& uri) {
  const std::string package_scheme = "package://";
  const std::string file_scheme = "file://";
  if (uri.rfind(file_scheme, 0) == 0) {
    return uri.substr(file_scheme.size());
  }
  if (uri.rfind(package_scheme, 0) != 0) {
    return uri;
  }
  const std::string rest = uri.substr(package_scheme.size());
  const std::size_t slash = rest.find('/');
  const std::string package = rest.substr(0, slash);
  const std::string package_path = ros::package::getPath(package);
  if (package_path.empty()) {
    return "";
  }
  return slash == std::string::npos ? package_path : package_path + rest.substr(slash);
}

}  // namespace freeform_inspection_ros
