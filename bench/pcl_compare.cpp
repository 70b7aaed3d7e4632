// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// pcl_compare: our pipeline against PCL's standard registration (pcl_pipeline.h: voxel grid,
// normals, FPFH, SampleConsensusPrerejective, point-to-plane ICP), side by side in one process
// on identical cases from makeSyntheticScan (seed = first seed + case number, as
// registration_eval). Each part is prepared once per method (our loadModel, PCL's CAD sample and
// features); then every scan goes to both. Prints markdown tables; --json FILE writes all of it.
//
//   pcl_compare --cad FILE [--cad-scale S] [--cad FILE [--cad-scale S]]...
//               [--sets NAME,...] [--cases N] [--first-seed N] [--method both|ours|pcl]
//               [--noise R] [--partial] [--outliers F] [--points N]   (one custom set instead)
//               [--no-normals] [--scaling [--sizes N,N,...]] [--json FILE]
//   pcl_compare --dragon DIR [--min-surface S] [--method both|ours|pcl] [--json FILE]
//
// --cad-scale applies to the --cad before it. Sets: full0.5 full1 full2 partial0.5 partial1
// partial2 outliers20 sparse3k (default: all). --scaling times the first part at each size
// (full view, 0.5 % noise). --no-normals (or FI_NO_NORMALS set) strips the scanner normals.
// --dragon runs the real range scans of the Stanford dragon instead (dragon_views.h: each view
// plays the CAD for the next one, bare points for both methods); --min-surface sets our
// registration.min_surface_on_cad, as dragon_eval's does (two views share 55–94 % of their
// surface, which the default 0.8 refuses below it).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "dragon_views.h"
#include "pcl_compare_report.h"
#include "pcl_pipeline.h"
#include "pose_error.h"
#include <malloc.h>

#include "freeform_inspection/model.h"
#include "freeform_inspection/pipeline.h"
#include "freeform_inspection/synthetic_scan.h"

namespace fi = freeform_inspection;
namespace fb = freeform_inspection::bench;

namespace {

using Clock = std::chrono::steady_clock;

struct CaseSet {
  std::string name;   // command-line name
  std::string label;  // table label
  fi::SyntheticScanConfig scan;
};

fi::SyntheticScanConfig scanConfig(double noise, bool partial, double outliers, std::size_t n) {
  fi::SyntheticScanConfig config;
  config.noise_ratio = noise;
  config.partial = partial;
  config.outlier_fraction = outliers;
  config.points = n;
  return config;
}

// The label of the dragon's set (--dragon).
const char* const kDragonSet = "dragon range scans, view to next view";

std::vector<CaseSet> standardSets() {
  return {{"full0.5", "full 0.5%", scanConfig(0.005, false, 0.0, 30000)},
          {"full1", "full 1%", scanConfig(0.01, false, 0.0, 30000)},
          {"full2", "full 2%", scanConfig(0.02, false, 0.0, 30000)},
          {"partial0.5", "partial 0.5%", scanConfig(0.005, true, 0.0, 30000)},
          {"partial1", "partial 1%", scanConfig(0.01, true, 0.0, 30000)},
          {"partial2", "partial 2%", scanConfig(0.02, true, 0.0, 30000)},
          {"outliers20", "full 0.5% + 20% outliers", scanConfig(0.005, false, 0.2, 30000)},
          {"sparse3k", "full 0.5%, 3k points", scanConfig(0.005, false, 0.0, 3000)}};
}

struct Part {
  std::string path;
  double scale = 1.0;
};

struct Options {
  std::vector<Part> parts;
  std::vector<std::string> set_names;
  bool custom = false;
  fi::SyntheticScanConfig custom_scan = scanConfig(0.005, false, 0.0, 30000);
  int cases = 3;
  std::uint64_t first_seed = 1;
  bool run_ours = true;
  bool run_pcl = true;
  bool scan_normals = std::getenv("FI_NO_NORMALS") == nullptr;
  bool scaling = false;
  std::vector<std::size_t> sizes = {10000, 30000, 100000, 300000, 1000000};
  std::string json;
  std::string dragon_dir;     // --dragon: the real range scans instead of generated cases
  double min_surface = -1.0;  // --min-surface: ours' registration.min_surface_on_cad (< 0: default)
};

std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    items.push_back(item);
  }
  return items;
}

bool parse(int argc, char** argv, Options* o) {
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    const bool has_value = i + 1 < argc;
    if (flag == "--cad" && has_value) {
      o->parts.push_back({argv[++i], 1.0});
    } else if (flag == "--cad-scale" && has_value && !o->parts.empty()) {
      o->parts.back().scale = std::atof(argv[++i]);
    } else if (flag == "--sets" && has_value) {
      o->set_names = splitCommas(argv[++i]);
    } else if (flag == "--cases" && has_value) {
      o->cases = std::atoi(argv[++i]);
    } else if (flag == "--first-seed" && has_value) {
      o->first_seed = static_cast<std::uint64_t>(std::atol(argv[++i]));
    } else if (flag == "--method" && has_value) {
      const std::string method = argv[++i];
      o->run_ours = method == "both" || method == "ours";
      o->run_pcl = method == "both" || method == "pcl";
    } else if (flag == "--noise" && has_value) {
      o->custom = true;
      o->custom_scan.noise_ratio = std::atof(argv[++i]);
    } else if (flag == "--outliers" && has_value) {
      o->custom = true;
      o->custom_scan.outlier_fraction = std::atof(argv[++i]);
    } else if (flag == "--points" && has_value) {
      o->custom = true;
      o->custom_scan.points = static_cast<std::size_t>(std::atol(argv[++i]));
    } else if (flag == "--partial") {
      o->custom = true;
      o->custom_scan.partial = true;
    } else if (flag == "--no-normals") {
      o->scan_normals = false;
    } else if (flag == "--scaling") {
      o->scaling = true;
    } else if (flag == "--sizes" && has_value) {
      o->sizes.clear();
      for (const auto& size : splitCommas(argv[++i])) {
        o->sizes.push_back(static_cast<std::size_t>(std::atol(size.c_str())));
      }
    } else if (flag == "--json" && has_value) {
      o->json = argv[++i];
    } else if (flag == "--dragon" && has_value) {
      o->dragon_dir = argv[++i];
    } else if (flag == "--min-surface" && has_value) {
      o->min_surface = std::atof(argv[++i]);
    } else {
      return false;
    }
  }
  return (!o->parts.empty() || !o->dragon_dir.empty()) && o->cases > 0 &&
         (o->run_ours || o->run_pcl);
}

// Peak resident memory of one phase. Linux resets the high-water mark VmHWM to the current
// RSS when "5" is written to /proc/self/clear_refs; malloc_trim first returns freed heap to the
// system, so that a phase reusing memory an earlier phase freed still shows as growth. Where
// clear_refs is refused the peak is unknown (-1), never a number from another phase.
class PeakMeter {
 public:
  void start() {
    malloc_trim(0);
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
    clear.close();
    valid_ = !clear.fail();
    base_kib_ = statusKib("VmRSS:");
  }
  double stopMib() const {
    return valid_ ? static_cast<double>(statusKib("VmHWM:") - base_kib_) / 1024.0 : -1.0;
  }

 private:
  static long statusKib(const std::string& key) {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);) {
      if (line.compare(0, key.size(), key) == 0) {
        return std::atol(line.c_str() + key.size());
      }
    }
    return 0;
  }
  bool valid_ = false;
  long base_kib_ = 0;
};

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// RMS distance [m] from the true surface points (outliers excluded), moved by `T_cad_scan`, to
// the exact CAD triangles; at most 30,000 evenly spread points.
double surfaceRms(const fi::Model& model,
                  const fi::SyntheticScan& generated,
                  const Eigen::Isometry3d& T_cad_scan) {
  const std::size_t surface = generated.scan.points.size() - generated.outliers;
  const std::size_t stride = std::max<std::size_t>(1, surface / 30000);
  fi::Points moved;
  for (std::size_t i = 0; i < surface; i += stride) {
    moved.push_back(T_cad_scan * generated.scan.points[i]);
  }
  double sum = 0.0;
  for (const auto& closest : model.query().closest(moved)) {
    sum += closest.distance * closest.distance;
  }
  return std::sqrt(sum / static_cast<double>(std::max<std::size_t>(1, moved.size())));
}

// Fills the pose errors of `record` for `T_cad_scan` against the truth.
void scorePose(const fi::Model& model,
               const fi::SyntheticScan& generated,
               double sigma,
               const Eigen::Isometry3d& T_cad_scan,
               fb::CaseRecord* record) {
  const std::size_t surface = generated.scan.points.size() - generated.outliers;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < surface; ++i) {
    centroid += generated.scan.points[i] / static_cast<double>(surface);
  }
  const double diagonal = model.bounds().diagonal();
  record->rotation_deg = fb::rotationErrorDeg(T_cad_scan, generated.T_cad_scan);
  record->translation_ratio =
      (T_cad_scan * centroid - generated.T_cad_scan * centroid).norm() / diagonal;
  record->right = record->rotation_deg < 2.0 && record->translation_ratio < 0.01;
  // Without noise there is no σ to compare with.
  const double unit = sigma > 0.0 ? sigma : std::numeric_limits<double>::quiet_NaN();
  record->rms_over_sigma = surfaceRms(model, generated, T_cad_scan) / unit;
  record->truth_rms_over_sigma = surfaceRms(model, generated, generated.T_cad_scan) / unit;
}

// Our inspect() on one case; the registration time leaves out the deviation stage.
fb::CaseRecord runOurs(const fi::Model& model,
                       const fi::Scan& scan,
                       const fi::SyntheticScan& generated,
                       double sigma,
                       const fi::PipelineConfig& config) {
  fb::CaseRecord record;
  record.method = "ours";
  PeakMeter meter;
  meter.start();
  const auto start = Clock::now();
  const fi::InspectionResult result = fi::inspect(model, scan, config);
  record.seconds_total = secondsSince(start);
  record.peak_mib = meter.stopMib();
  for (const auto& timing : result.timings) {
    record.timings.emplace_back(timing.stage, timing.seconds);
    // Registration alone: every stage but the deviation (the verdict is trivial).
    if (timing.stage != "deviation" && timing.stage != "total") {
      record.seconds += timing.seconds;
    }
  }
  record.status = fi::toString(result.registration);
  record.message = result.status.message;
  record.claimed = result.registration == fi::RegistrationStatus::kOk;
  scorePose(model, generated, sigma, result.T_cad_scan, &record);
  record.success = record.right && record.claimed;
  return record;
}

// PCL's pipeline on one case; success is the pose alone (PCL has no "ambiguous").
fb::CaseRecord runPcl(fb::PclRegistration* pcl,
                      const fi::Model& model,
                      const fi::Scan& scan,
                      const fi::SyntheticScan& generated,
                      double sigma,
                      std::uint64_t seed) {
  fb::CaseRecord record;
  record.method = "pcl";
  PeakMeter meter;
  meter.start();
  const fb::PclResult result = pcl->align(scan, seed);
  record.peak_mib = meter.stopMib();
  record.timings = result.timings;
  record.seconds = result.timings.back().second;
  record.seconds_total = record.seconds;
  record.status = result.converged ? "converged" : "not_converged";
  record.claimed = result.converged;
  scorePose(model, generated, sigma, result.T_cad_scan, &record);
  record.success = record.right;
  return record;
}

std::string fileName(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string cpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.compare(0, 10, "model name") == 0) {
      return line.substr(line.find(':') + 2);
    }
  }
  return "unknown";
}

// The part's record once its model is made (what making it cost counts only when ours runs), and
// PCL's once-per-part preparation of it when PCL runs, its time and memory into `prepared`.
std::unique_ptr<fb::PclRegistration> prepareMethods(const fi::Model& model,
                                                    const Options& options,
                                                    const fb::PclPipelineConfig& pcl_config,
                                                    double model_seconds,
                                                    double model_peak_mib,
                                                    fb::PartRecord* prepared) {
  if (options.run_ours) {
    prepared->ours_seconds = model_seconds;
    prepared->ours_peak_mib = model_peak_mib;
  }
  prepared->vertices = model.mesh().vertices.size();
  prepared->diagonal = model.bounds().diagonal();
  if (!options.run_pcl) {
    return nullptr;
  }
  PeakMeter meter;
  meter.start();
  auto pcl = std::make_unique<fb::PclRegistration>(model.mesh(), pcl_config);
  prepared->pcl_peak_mib = meter.stopMib();
  prepared->pcl_seconds = pcl->cadStats().seconds;
  prepared->pcl_dense_points = pcl->cadStats().dense_points;
  prepared->pcl_feature_points = pcl->cadStats().feature_points;
  return pcl;
}

// One case through ours (unless `ours` is null) and PCL (unless `pcl` is null), each record
// logged as a line on stderr and appended to `records`.
void runCase(const fi::Model& model,
             const fi::PipelineConfig* ours,
             fb::PclRegistration* pcl,
             const fi::SyntheticScan& generated,
             const fi::Scan& scan,
             double sigma,
             std::uint64_t seed,
             const std::string& part,
             const std::string& set,
             std::vector<fb::CaseRecord>* records) {
  std::vector<fb::CaseRecord> pair;
  if (ours != nullptr) {
    pair.push_back(runOurs(model, scan, generated, sigma, *ours));
  }
  if (pcl != nullptr) {
    pair.push_back(runPcl(pcl, model, scan, generated, sigma, seed));
  }
  for (fb::CaseRecord& record : pair) {
    record.part = part;
    record.set = set;
    record.seed = seed;
    record.points = scan.points.size();
    std::fprintf(stderr,
                 "%s | %s | seed %llu | %s %s rot %.3f deg t %.4f %%L rms/σ %.2f %.2f s\n",
                 record.part.c_str(),
                 record.set.c_str(),
                 static_cast<unsigned long long>(record.seed),
                 record.method.c_str(),
                 record.status.c_str(),
                 record.rotation_deg,
                 record.translation_ratio * 100.0,
                 record.rms_over_sigma,
                 record.seconds);
    records->push_back(record);
  }
}

// The Stanford dragon's real range scans: each view the CAD of the next (both methods prepare
// it like a part), the scan bare points in its own frame (no normals for either method), the
// truth the turntable's calibration. Real scans have no σ to compare the RMS with.
bool runDragon(const Options& options,
               const fi::PipelineConfig& ours_config,
               std::vector<fb::PartRecord>* parts,
               std::vector<fb::CaseRecord>* records) {
  std::vector<fb::DragonPair> pairs;
  std::string error;
  if (!fb::readDragonPairs(options.dragon_dir, 1, &pairs, &error)) {
    std::fprintf(stderr, "pcl_compare: %s\n", error.c_str());
    return false;
  }
  fb::PclPipelineConfig pcl_config;
  pcl_config.use_scan_normals = false;
  std::uint64_t seed = options.first_seed;
  for (const fb::DragonPair& pair : pairs) {
    fb::PartRecord prepared;
    prepared.part = pair.cad_view;
    PeakMeter meter;
    meter.start();
    const auto start = Clock::now();
    const fi::Model model(pair.cad, pair.cad_view, pair.cad_view);
    if (!model.query().status().ok() || !model.descriptors().status.ok()) {
      std::fprintf(stderr, "pcl_compare: %s cannot be a CAD\n", pair.cad_view.c_str());
      return false;
    }
    const std::unique_ptr<fb::PclRegistration> pcl =
        prepareMethods(model, options, pcl_config, secondsSince(start), meter.stopMib(), &prepared);
    parts->push_back(prepared);
    fi::SyntheticScan truth;
    truth.scan.points = pair.scan;
    truth.T_cad_scan = pair.T_cad_scan;
    runCase(model,
            options.run_ours ? &ours_config : nullptr,
            pcl.get(),
            truth,
            truth.scan,
            0.0,
            seed++,
            prepared.part,
            kDragonSet,
            records);
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!parse(argc, argv, &options)) {
    std::fprintf(stderr,
                 "usage: pcl_compare --cad FILE [--cad-scale S]... [--sets NAME,...] "
                 "[--cases N] [--first-seed N] [--method both|ours|pcl] [--noise R] [--partial] "
                 "[--outliers F] [--points N] [--no-normals] [--scaling [--sizes N,...]] "
                 "[--json FILE]\n       pcl_compare --dragon DIR [--min-surface S] "
                 "[--method both|ours|pcl] [--json FILE]\n");
    return 2;
  }
  std::vector<CaseSet> sets;
  if (!options.dragon_dir.empty()) {
    sets.push_back({"dragon", kDragonSet, fi::SyntheticScanConfig()});
    options.parts.clear();
    options.cases = 1;  // one scan per view pair
  } else if (options.scaling) {
    for (const std::size_t size : options.sizes) {
      sets.push_back({"scaling", std::to_string(size), scanConfig(0.005, false, 0.0, size)});
    }
    options.parts.resize(1);
  } else if (options.custom) {
    sets.push_back({"custom", "custom", options.custom_scan});
  } else {
    for (const auto& set : standardSets()) {
      if (options.set_names.empty() ||
          std::find(options.set_names.begin(), options.set_names.end(), set.name) !=
              options.set_names.end()) {
        sets.push_back(set);
      }
    }
  }
  if (sets.empty()) {
    std::fprintf(stderr, "pcl_compare: no known set in --sets\n");
    return 2;
  }

  fb::RunInfo info;
  for (int i = 0; i < argc; ++i) {
    info.command += (i > 0 ? " " : "") + std::string(argv[i]);
  }
  info.cpu = cpuModel();
  info.threads = std::thread::hardware_concurrency();
  info.memory_method =
      "per call: VmHWM after resetting it (/proc/self/clear_refs) minus VmRSS before, after "
      "malloc_trim";
  info.cases = options.cases;
  info.scaling = options.scaling;
  info.scan_normals = options.scan_normals && options.dragon_dir.empty();
  fb::PclPipelineConfig pcl_config;
  pcl_config.use_scan_normals = options.scan_normals;
  fi::PipelineConfig ours_config;
  if (options.min_surface >= 0.0) {
    ours_config.registration.min_surface_on_cad = options.min_surface;
  }

  std::vector<fb::PartRecord> parts;
  std::vector<fb::CaseRecord> records;
  if (!options.dragon_dir.empty() && !runDragon(options, ours_config, &parts, &records)) {
    return 2;
  }
  for (const Part& part : options.parts) {
    fb::PartRecord prepared;
    prepared.part = fileName(part.path);
    PeakMeter meter;
    meter.start();
    auto start = Clock::now();
    const fi::ModelLoadResult loaded = fi::loadModel(part.path, part.scale, "compare");
    if (!loaded.status.ok()) {
      std::fprintf(stderr, "pcl_compare: %s\n", loaded.status.message.c_str());
      return 2;
    }
    const fi::Model& model = *loaded.model;
    // The model is needed for the cases and the truth; its cost counts only when ours runs.
    const std::unique_ptr<fb::PclRegistration> pcl =
        prepareMethods(model, options, pcl_config, secondsSince(start), meter.stopMib(), &prepared);
    std::fprintf(stderr,
                 "# %s: %zu vertices, L = %.4f m; ours load %.2f s, PCL prep %.2f s\n",
                 prepared.part.c_str(),
                 prepared.vertices,
                 prepared.diagonal,
                 prepared.ours_seconds,
                 prepared.pcl_seconds);
    parts.push_back(prepared);

    for (const CaseSet& set : sets) {
      for (int c = 0; c < options.cases; ++c) {
        fi::SyntheticScanConfig config = set.scan;
        config.seed = options.first_seed + static_cast<std::uint64_t>(c);
        const fi::SyntheticScan generated = fi::makeSyntheticScan(model.query(), config);
        if (!generated.status.ok()) {
          std::fprintf(stderr, "pcl_compare: %s\n", generated.status.message.c_str());
          return 2;
        }
        fi::Scan scan = generated.scan;
        if (!options.scan_normals) {
          scan.normals.clear();
        }
        runCase(model,
                options.run_ours ? &ours_config : nullptr,
                pcl.get(),
                generated,
                scan,
                config.noise_ratio * prepared.diagonal,
                config.seed,
                prepared.part,
                set.label,
                &records);
      }
    }
  }

  std::vector<std::string> set_order;
  for (const auto& set : sets) {
    set_order.push_back(set.label);
  }
  if (options.scaling) {
    fb::printScalingTable(records);
  } else {
    fb::printCaseTables(records, parts, set_order, info);
  }
  if (!options.json.empty() && !fb::writeJson(options.json, records, parts, set_order, info)) {
    std::fprintf(stderr, "pcl_compare: cannot write %s\n", options.json.c_str());
    return 2;
  }
  return 0;
}
