// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "cli_options.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

namespace freeform_inspection {
namespace {

std::optional<double> parsePositive(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value) || value <= 0.0) {
    return std::nullopt;
  }
  return value;
}

// --initial-pose: 12 or 16 finite numbers, row-major, separated by spaces or commas; brackets are
// ignored, so the report's transform_cad_from_scan can be pasted as it is. A fourth row must be
// 0 0 0 1.
std::optional<std::vector<double>> parsePose(std::string text) {
  std::replace_if(
      text.begin(), text.end(), [](char c) { return c == ',' || c == '[' || c == ']'; }, ' ');
  std::istringstream stream(text);
  std::vector<double> numbers;
  std::string word;
  while (stream >> word) {
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    if (*end != '\0' || !std::isfinite(value)) {
      return std::nullopt;
    }
    numbers.push_back(value);
  }
  if (numbers.size() == 16) {
    if (numbers[12] != 0.0 || numbers[13] != 0.0 || numbers[14] != 0.0 || numbers[15] != 1.0) {
      return std::nullopt;
    }
    numbers.resize(12);
  }
  if (numbers.size() != 12) {
    return std::nullopt;
  }
  return numbers;
}

// Applies one "--flag value" pair; returns an error message or "".
std::string apply(const std::string& flag, const std::string& value, CliOptions* options) {
  const std::map<std::string, std::string*> paths = {{"--cad", &options->cad_path},
                                                     {"--scan", &options->scan_path},
                                                     {"--config", &options->config_path},
                                                     {"--regions", &options->regions_path},
                                                     {"--points", &options->points_path},
                                                     {"--report", &options->report_path},
                                                     {"--deviation", &options->deviation_path},
                                                     {"--html", &options->html_path},
                                                     {"--csv", &options->csv_directory},
                                                     {"--part-id", &options->part_id},
                                                     {"--model-cache", &options->model_cache}};
  if (const auto path = paths.find(flag); path != paths.end()) {
    *path->second = value;
    return "";
  }
  const std::map<std::string, double*> scales = {{"--cad-scale", &options->cad_scale},
                                                 {"--scan-scale", &options->scan_scale}};
  const auto number = parsePositive(value);
  if (const auto scale = scales.find(flag); scale != scales.end()) {
    if (!number) {
      return flag + " needs a positive number, got '" + value + "'";
    }
    *scale->second = *number;
    return "";
  }
  if (flag == "--initial-pose" || flag == "--fixed-pose") {
    const auto pose = parsePose(value);
    if (!pose) {
      return flag +
             " needs the scan-to-CAD transform as 12 numbers (its first three rows, "
             "row-major) or 16 ending in 0 0 0 1, got '" +
             value + "'";
    }
    (flag == "--initial-pose" ? options->initial_pose : options->fixed_pose) = *pose;
    return "";
  }
  if (flag == "--tolerance") {
    if (!number) {
      return "--tolerance needs a positive length in metres, got '" + value + "'";
    }
    options->tolerance = number;
    return "";
  }
  return "unknown option '" + flag + "' (see --help)";
}

}  // namespace

CliParseResult parseCliOptions(const std::vector<std::string>& args) {
  CliOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--help" || args[i] == "-h") {
      options.help = true;
      return {options, ""};
    }
    if (args[i] == "--no-model-cache") {
      options.no_model_cache = true;
      continue;
    }
    if (i + 1 >= args.size()) {
      return {std::nullopt, "option '" + args[i] + "' needs a value (see --help)"};
    }
    const std::string error = apply(args[i], args[i + 1], &options);
    if (!error.empty()) {
      return {std::nullopt, error};
    }
    ++i;
  }
  if (options.cad_path.empty() || options.scan_path.empty()) {
    return {std::nullopt, "both --cad and --scan are required (see --help)"};
  }
  if (!options.initial_pose.empty() && !options.fixed_pose.empty()) {
    return {std::nullopt,
            "--initial-pose (refine the pose) and --fixed-pose (inspect at it as it is) exclude "
            "each other"};
  }
  return {options, ""};
}

std::string cliUsage() {
  return "usage: freeform_inspect --cad CAD.{stl,ply,obj} --scan SCAN.{ply,pcd,stl,obj}\n"
         "                        [--cad-scale S] [--scan-scale S] [--tolerance T]\n"
         "                        [--config FILE.yaml] [--regions FILE.yaml]\n"
         "                        [--points FILE.yaml]\n"
         "                        [--report OUT.json] [--deviation OUT.ply]\n"
         "                        [--html OUT.html] [--csv DIR] [--part-id ID]\n"
         "                        [--model-cache DIR | --no-model-cache]\n"
         "                        [--initial-pose \"R11 R12 R13 TX R21 ... TZ\" |\n"
         "                         --fixed-pose \"R11 R12 R13 TX R21 ... TZ\"]\n"
         "\n"
         "Registers the scan to the CAD model from any pose and prints one JSON object.\n"
         "--initial-pose refines a known scan-to-CAD transform (a fixture's nominal pose; the\n"
         "report's transform_cad_from_scan pasted as it is) by ICP instead of searching;\n"
         "--fixed-pose inspects at the transform as it is, not registered (a locating fixture).\n"
         "--deviation writes the coloured deviation map (PLY, CAD frame) when the scan was\n"
         "registered; --html writes a self-contained report for people; --csv writes\n"
         "summary.csv, defects.csv, histogram.csv and regions.csv into DIR, lengths in mm, for\n"
         "spreadsheets and SPC tools (docs/reports.md); --part-id names the part (a serial) in\n"
         "the JSON, the HTML and the CSV summary.\n"
         "Lengths are metres after scaling: --cad-scale 0.001 reads a CAD file in millimetres,\n"
         "--tolerance 0.0002 is a band of +-0.2 mm.\n"
         "--regions names regions of the CAD (boxes in its frame, metres) with a tolerance of\n"
         "their own or left out of the verdict; each is reported and judged (docs/inspection.md).\n"
         "--points names comparison points on the CAD (positions in its frame, metres): the\n"
         "deviation read there from the scan, judged against a band of its own or the surface's.\n"
         "The CAD's descriptors and symmetries are kept between runs in --model-cache DIR\n"
         "(default $XDG_CACHE_HOME or ~/.cache, under freeform_inspection/models), so the next\n"
         "run on the same CAD skips computing them; --no-model-cache turns that off.\n"
         "Exit codes: 0 it ran (whatever the verdict), 2 bad input or usage (one line on "
         "stderr).\n";
}

std::string modelCacheDirectory(const CliOptions& options) {
  if (options.no_model_cache) {
    return "";
  }
  if (!options.model_cache.empty()) {
    return options.model_cache;
  }
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg != nullptr && xdg[0] == '/') {  // the XDG rule: a relative value is ignored
    return std::string(xdg) + "/freeform_inspection/models";
  }
  const char* home = std::getenv("HOME");
  if (home != nullptr && home[0] != '\0') {
    return std::string(home) + "/.cache/freeform_inspection/models";
  }
  return "";
}

}  // namespace freeform_inspection
