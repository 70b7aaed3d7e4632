// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "pcl_compare_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>

#include <nlohmann/json.hpp>

namespace freeform_inspection {
namespace bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double quantile(std::vector<double> values, double q) {
  // Unknown values (RMS / σ of a real scan, which has no σ) are left out, not sorted among.
  values.erase(
      std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
      values.end());
  if (values.empty()) {
    return kNaN;
  }
  std::sort(values.begin(), values.end());
  if (q == 0.5) {
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  }
  // Nearest rank: the smallest value with at least q of the values at or below it.
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  return values[std::max<std::size_t>(rank, 1) - 1];
}

// The numbers of one row of the main table: one method on one case set, over every part.
struct Summary {
  std::string set;
  std::string method;
  int cases = 0;
  int success = 0;
  int wrong_claimed = 0;  // a wrong pose the method vouched for
  std::map<std::string, int> statuses;
  double median_s = kNaN;
  double p90_s = kNaN;
  double median_total_s = kNaN;  // ours: the whole inspect()
  double rotation_deg = kNaN;    // medians over the successful cases
  double translation_ratio = kNaN;
  double rms_over_sigma = kNaN;
  double truth_rms_over_sigma = kNaN;
  double max_peak_mib = kNaN;
};

Summary summarise(const std::vector<CaseRecord>& records,
                  const std::string& set,
                  const std::string& method) {
  Summary s;
  s.set = set;
  s.method = method;
  std::vector<double> seconds, totals, rotation, translation, rms, truth_rms, peaks;
  for (const auto& r : records) {
    if ((r.set != set && !set.empty()) || r.method != method) {
      continue;
    }
    ++s.cases;
    s.success += r.success ? 1 : 0;
    s.wrong_claimed += r.claimed && !r.right ? 1 : 0;
    ++s.statuses[r.status];
    seconds.push_back(r.seconds);
    totals.push_back(r.seconds_total);
    if (r.peak_mib >= 0.0) {
      peaks.push_back(r.peak_mib);
    }
    if (r.success) {
      rotation.push_back(r.rotation_deg);
      translation.push_back(r.translation_ratio);
      rms.push_back(r.rms_over_sigma);
      truth_rms.push_back(r.truth_rms_over_sigma);
    }
  }
  s.median_s = quantile(seconds, 0.5);
  s.p90_s = quantile(seconds, 0.9);
  s.median_total_s = quantile(totals, 0.5);
  s.rotation_deg = quantile(rotation, 0.5);
  s.translation_ratio = quantile(translation, 0.5);
  s.rms_over_sigma = quantile(rms, 0.5);
  s.truth_rms_over_sigma = quantile(truth_rms, 0.5);
  s.max_peak_mib = quantile(peaks, 1.0);
  return s;
}

std::vector<std::string> methodsIn(const std::vector<CaseRecord>& records) {
  std::vector<std::string> methods;
  for (const char* method : {"ours", "pcl"}) {
    if (std::any_of(records.begin(), records.end(), [&](const CaseRecord& r) {
          return r.method == method;
        })) {
      methods.emplace_back(method);
    }
  }
  return methods;
}

std::string number(double value, const char* format) {
  if (!std::isfinite(value)) {
    return "–";
  }
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

std::string outcome(const Summary& s) {
  std::string text;
  for (const auto& [status, count] : s.statuses) {
    text += (text.empty() ? "" : ", ") + status + " " + std::to_string(count);
  }
  return text;
}

void printSummaryRow(const Summary& s) {
  std::printf("| %s | %s | %d/%d | %d | %s | %s | %s | %s | %s (%s) | %s | %s |\n",
              s.set.empty() ? "**all sets**" : s.set.c_str(),
              s.method == "ours" ? "ours" : "PCL",
              s.success,
              s.cases,
              s.wrong_claimed,
              number(s.median_s, "%.2f").c_str(),
              number(s.p90_s, "%.2f").c_str(),
              number(s.rotation_deg, "%.3f").c_str(),
              number(s.translation_ratio * 100.0, "%.3f").c_str(),
              number(s.rms_over_sigma, "%.2f").c_str(),
              number(s.truth_rms_over_sigma, "%.2f").c_str(),
              number(s.max_peak_mib, "%.0f").c_str(),
              outcome(s).c_str());
}

// Median of one stage's time over the records of one size and method.
double medianStage(const std::vector<const CaseRecord*>& rows, const std::string& stage) {
  std::vector<double> values;
  for (const CaseRecord* r : rows) {
    for (const auto& [name, seconds] : r->timings) {
      if (name == stage) {
        values.push_back(seconds);
      }
    }
  }
  return quantile(values, 0.5);
}

const std::vector<std::string>& oursStages() {
  static const std::vector<std::string> stages = {"clean",
                                                  "supports",
                                                  "descriptors",
                                                  "features",
                                                  "correspondences",
                                                  "global_registration",
                                                  "icp",
                                                  "verification",
                                                  "deviation"};
  return stages;
}

const std::vector<std::string>& pclStages() {
  static const std::vector<std::string> stages = {
      "convert", "voxel_grid", "normals", "fpfh", "sac", "icp"};
  return stages;
}

// Scan sizes (set labels) in the order first seen, and the records of each per method.
using SizeGroups =
    std::vector<std::pair<std::string, std::map<std::string, std::vector<const CaseRecord*>>>>;

SizeGroups bySize(const std::vector<CaseRecord>& records) {
  SizeGroups out;
  for (const auto& r : records) {
    auto it = std::find_if(out.begin(), out.end(), [&](const auto& e) { return e.first == r.set; });
    if (it == out.end()) {
      out.push_back({r.set, {}});
      it = out.end() - 1;
    }
    it->second[r.method].push_back(&r);
  }
  return out;
}

double medianOf(const std::vector<const CaseRecord*>& rows, double CaseRecord::*field) {
  std::vector<double> values;
  for (const CaseRecord* r : rows) {
    values.push_back(r->*field);
  }
  return quantile(values, 0.5);
}

int successes(const std::vector<const CaseRecord*>& rows) {
  return static_cast<int>(
      std::count_if(rows.begin(), rows.end(), [](const CaseRecord* r) { return r->success; }));
}

}  // namespace

void printCaseTables(const std::vector<CaseRecord>& records,
                     const std::vector<PartRecord>& parts,
                     const std::vector<std::string>& set_order,
                     const RunInfo& info) {
  const auto methods = methodsIn(records);
  std::printf("%d cases per part and set, %zu parts; scans %s normals; CPU %s, %u threads\n\n",
              info.cases,
              parts.size(),
              info.scan_normals ? "with" : "without",
              info.cpu.c_str(),
              info.threads);
  std::printf(
      "| case set | method | success | wrong but claimed | median s | p90 s | rot. error [°] | "
      "centroid error [%% L] | RMS/σ (true pose) | peak [MiB] | outcome |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& set : set_order) {
    for (const auto& method : methods) {
      printSummaryRow(summarise(records, set, method));
    }
  }
  for (const auto& method : methods) {
    printSummaryRow(summarise(records, "", method));
  }

  if (methods.size() == 2) {
    std::printf(
        "\n| case set | ours median s | PCL median s | ours/PCL | ours inspect() median s |\n");
    std::printf("|---|---|---|---|---|\n");
    for (const auto& set : set_order) {
      const Summary ours = summarise(records, set, "ours");
      const Summary pcl = summarise(records, set, "pcl");
      std::printf("| %s | %.2f | %.2f | %.2f | %.2f |\n",
                  set.c_str(),
                  ours.median_s,
                  pcl.median_s,
                  ours.median_s / pcl.median_s,
                  ours.median_total_s);
    }
  }

  std::printf("\nSuccesses per part (%s, out of %d):\n\n| part |",
              methods.size() == 2         ? "ours / PCL"
              : methods.front() == "ours" ? "ours"
                                          : "PCL",
              info.cases);
  for (const auto& set : set_order) {
    std::printf(" %s |", set.c_str());
  }
  std::printf("\n|---|");
  for (std::size_t i = 0; i < set_order.size(); ++i) {
    std::printf("---|");
  }
  for (const auto& part : parts) {
    std::printf("\n| %s |", part.part.c_str());
    for (const auto& set : set_order) {
      std::string cell;
      for (const auto& method : methods) {
        const auto n = std::count_if(records.begin(), records.end(), [&](const CaseRecord& r) {
          return r.part == part.part && r.set == set && r.method == method && r.success;
        });
        cell += (cell.empty() ? "" : " / ") + std::to_string(n);
      }
      std::printf(" %s |", cell.c_str());
    }
  }

  std::printf(
      "\n\n| part | vertices | L [m] | ours load [s] | ours peak [MiB] | PCL prep [s] | "
      "PCL peak [MiB] | PCL dense / feature points |\n|---|---|---|---|---|---|---|---|\n");
  for (const auto& part : parts) {
    std::printf("| %s | %zu | %.3f | %s | %s | %s | %s | %zu / %zu |\n",
                part.part.c_str(),
                part.vertices,
                part.diagonal,
                number(part.ours_seconds, "%.2f").c_str(),
                number(part.ours_peak_mib, "%.0f").c_str(),
                number(part.pcl_seconds, "%.2f").c_str(),
                number(part.pcl_peak_mib, "%.0f").c_str(),
                part.pcl_dense_points,
                part.pcl_feature_points);
  }
}

void printScalingTable(const std::vector<CaseRecord>& records) {
  std::printf("| points |");
  for (const auto& stage : oursStages()) {
    std::printf(" ours %s |", stage.c_str());
  }
  std::printf(" **ours registration** |");
  for (const auto& stage : pclStages()) {
    std::printf(" PCL %s |", stage.c_str());
  }
  std::printf(" **PCL total** | ours/PCL | success ours / PCL | peak MiB ours / PCL |\n|");
  for (std::size_t i = 0; i < oursStages().size() + pclStages().size() + 6; ++i) {
    std::printf("---|");
  }
  std::printf("\n");
  for (const auto& [size, methods] : bySize(records)) {
    const auto ours = methods.count("ours") ? methods.at("ours") : std::vector<const CaseRecord*>();
    const auto pcl = methods.count("pcl") ? methods.at("pcl") : std::vector<const CaseRecord*>();
    std::printf("| %s |", size.c_str());
    for (const auto& stage : oursStages()) {
      std::printf(" %s |", number(medianStage(ours, stage), "%.3f").c_str());
    }
    const double ours_s = medianOf(ours, &CaseRecord::seconds);
    const double pcl_s = medianOf(pcl, &CaseRecord::seconds);
    std::printf(" **%s** |", number(ours_s, "%.2f").c_str());
    for (const auto& stage : pclStages()) {
      std::printf(" %s |", number(medianStage(pcl, stage), "%.3f").c_str());
    }
    std::printf(" **%s** | %s | %d/%zu / %d/%zu | %s / %s |\n",
                number(pcl_s, "%.2f").c_str(),
                number(ours_s / pcl_s, "%.2f").c_str(),
                successes(ours),
                ours.size(),
                successes(pcl),
                pcl.size(),
                number(medianOf(ours, &CaseRecord::peak_mib), "%.0f").c_str(),
                number(medianOf(pcl, &CaseRecord::peak_mib), "%.0f").c_str());
  }
}

bool writeJson(const std::string& path,
               const std::vector<CaseRecord>& records,
               const std::vector<PartRecord>& parts,
               const std::vector<std::string>& set_order,
               const RunInfo& info) {
  using Json = nlohmann::ordered_json;
  Json root;
  root["run"] = {{"command", info.command},
                 {"cpu", info.cpu},
                 {"threads", info.threads},
                 {"memory", info.memory_method},
                 {"cases", info.cases},
                 {"scan_normals", info.scan_normals}};
  root["parts"] = Json::array();
  for (const auto& p : parts) {
    root["parts"].push_back({{"part", p.part},
                             {"vertices", p.vertices},
                             {"diagonal_m", p.diagonal},
                             {"ours_load_s", p.ours_seconds},
                             {"ours_peak_mib", p.ours_peak_mib},
                             {"pcl_prep_s", p.pcl_seconds},
                             {"pcl_peak_mib", p.pcl_peak_mib},
                             {"pcl_dense_points", p.pcl_dense_points},
                             {"pcl_feature_points", p.pcl_feature_points}});
  }
  root["cases"] = Json::array();
  for (const auto& r : records) {
    Json timings = Json::object();
    for (const auto& [stage, seconds] : r.timings) {
      timings[stage] = seconds;
    }
    root["cases"].push_back({{"part", r.part},
                             {"set", r.set},
                             {"method", r.method},
                             {"seed", r.seed},
                             {"points", r.points},
                             {"status", r.status},
                             {"message", r.message},
                             {"claimed", r.claimed},
                             {"right", r.right},
                             {"success", r.success},
                             {"rotation_deg", r.rotation_deg},
                             {"translation_ratio", r.translation_ratio},
                             {"rms_over_sigma", r.rms_over_sigma},
                             {"truth_rms_over_sigma", r.truth_rms_over_sigma},
                             {"seconds", r.seconds},
                             {"seconds_total", r.seconds_total},
                             {"peak_mib", r.peak_mib},
                             {"timings_s", timings}});
  }
  const auto methods = methodsIn(records);
  root["summary"] = Json::array();
  for (const auto& set : set_order) {
    for (const auto& method : methods) {
      const Summary s = summarise(records, set, method);
      root["summary"].push_back({{"set", s.set},
                                 {"method", s.method},
                                 {"cases", s.cases},
                                 {"success", s.success},
                                 {"wrong_but_claimed", s.wrong_claimed},
                                 {"statuses", s.statuses},
                                 {"median_s", s.median_s},
                                 {"p90_s", s.p90_s},
                                 {"median_total_s", s.median_total_s},
                                 {"median_rotation_deg", s.rotation_deg},
                                 {"median_translation_ratio", s.translation_ratio},
                                 {"median_rms_over_sigma", s.rms_over_sigma},
                                 {"median_truth_rms_over_sigma", s.truth_rms_over_sigma},
                                 {"max_peak_mib", s.max_peak_mib}});
    }
  }
  // Per scan size (the scaling run only): median stage times, for bench/plot_scaling.py.
  root["scaling"] = Json::array();
  for (const auto& [size, by_method] : info.scaling ? bySize(records) : SizeGroups()) {
    for (const auto& [method, rows] : by_method) {
      Json stages = Json::object();
      for (const auto& stage : method == "ours" ? oursStages() : pclStages()) {
        stages[stage] = medianStage(rows, stage);
      }
      root["scaling"].push_back({{"set", size},
                                 {"method", method},
                                 {"points", rows.front()->points},
                                 {"cases", rows.size()},
                                 {"success", successes(rows)},
                                 {"median_s", medianOf(rows, &CaseRecord::seconds)},
                                 {"median_total_s", medianOf(rows, &CaseRecord::seconds_total)},
                                 {"median_peak_mib", medianOf(rows, &CaseRecord::peak_mib)},
                                 {"median_stage_s", stages}});
    }
  }
  std::ofstream out(path);
  out << root.dump(1) << "\n";
  return static_cast<bool>(out);
}

}  // namespace bench
}  // namespace freeform_inspection
