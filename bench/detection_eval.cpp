// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// What the inspection finds, through the whole pipeline from an unknown pose (docs/accuracy.md):
// generated scans (synthetic_scan.h) of a CAD at noise σ, judged against a band of ±K σ, clean
// and with one spherical-cap dent (or bump) pressed in at a random place of the view, of several
// base radii and of depths from inside the band to well beyond it.
//
//   detection_eval --cad FILE [--cad-scale S] [--noise R] [--band K] [--cases N]
//                  [--first-seed N] [--depths D,D,...] [--radii R,R,...] [--partial]
//                  [--points N] [--bumps]
//
// R: noise σ × the CAD diagonal L (default 0.0002); K: the band's half width in σ (default 4);
// D: the defect's depth × the band (default 0.5,0.8,1.2,1.5,2,3); radii × L (default
// 0.01,0.02,0.04). For each seed, a clean scan gives the false-reject rate and the error the
// registration adds to every deviation (measured minus the deviation at the true pose); then one
// defect, centred under a surface point of the view drawn by the seed, pressed in at every
// radius and depth, gives the detection rates.
// A defect is found when a region of its sign has its centroid within the defect's radius of
// its centre (more than one such region: found in pieces); any other region is a false call.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "pose_error.h"

#include "freeform_inspection/deviation.h"
#include "freeform_inspection/model.h"
#include "freeform_inspection/pipeline.h"
#include "freeform_inspection/surface_defect.h"
#include "freeform_inspection/synthetic_scan.h"

namespace fi = freeform_inspection;

namespace {

struct Options {
  std::string cad;
  double cad_scale = 1.0;
  fi::SyntheticScanConfig scan;
  double band_sigmas = 4.0;
  int cases = 8;
  std::uint64_t first_seed = 1;
  std::vector<double> depths = {0.5, 0.8, 1.2, 1.5, 2.0, 3.0};
  std::vector<double> radii = {0.01, 0.02, 0.04};
  bool bumps = false;
};

std::vector<double> parseList(const std::string& text) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    values.push_back(std::atof(item.c_str()));
  }
  return values;
}

bool parse(int argc, char** argv, Options* options) {
  options->scan.noise_ratio = 0.0002;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    const bool has_value = i + 1 < argc;
    if (flag == "--cad" && has_value) {
      options->cad = argv[++i];
    } else if (flag == "--cad-scale" && has_value) {
      options->cad_scale = std::atof(argv[++i]);
    } else if (flag == "--noise" && has_value) {
      options->scan.noise_ratio = std::atof(argv[++i]);
    } else if (flag == "--band" && has_value) {
      options->band_sigmas = std::atof(argv[++i]);
    } else if (flag == "--cases" && has_value) {
      options->cases = std::atoi(argv[++i]);
    } else if (flag == "--first-seed" && has_value) {
      options->first_seed = static_cast<std::uint64_t>(std::atol(argv[++i]));
    } else if (flag == "--depths" && has_value) {
      options->depths = parseList(argv[++i]);
    } else if (flag == "--radii" && has_value) {
      options->radii = parseList(argv[++i]);
    } else if (flag == "--points" && has_value) {
      options->scan.points = static_cast<std::size_t>(std::atol(argv[++i]));
    } else if (flag == "--partial") {
      options->scan.partial = true;
    } else if (flag == "--bumps") {
      options->bumps = true;
    } else {
      return false;
    }
  }
  return !options->cad.empty() && options->cases > 0 && options->scan.noise_ratio > 0.0 &&
         options->band_sigmas > 0.0 && !options->depths.empty() && !options->radii.empty();
}

double median(std::vector<double> values) {
  if (values.empty()) {
    return std::nan("");
  }
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// The error the registration adds to each deviation: the deviation measured at the registered
// pose minus the one at the true pose, for the same scan points. RMS, 95th percentile and
// largest magnitude [m] over the points matched both ways.
struct AddedError {
  double rms = 0.0;
  double p95 = 0.0;
  double max = 0.0;
};

AddedError registrationError(const fi::Model& model,
                             const fi::InspectionResult& result,
                             const fi::Scan& scan,
                             const Eigen::Isometry3d& truth,
                             const fi::DeviationConfig& config) {
  const fi::DeviationMap& map = result.deviation_map;
  const Eigen::Isometry3d T_true_registered = truth * result.T_cad_scan.inverse();
  fi::Points at_truth;
  at_truth.reserve(map.size());
  for (const auto& p : map.points) {
    at_truth.push_back(T_true_registered * p);
  }
  fi::Points normals;  // the scanner's, as the pipeline measures along them
  for (const auto& n : scan.normals) {
    normals.push_back(truth.linear() * n);
  }
  const fi::SurfaceDistances exact =
      fi::measureDeviation(model,
                           at_truth,
                           config.max_distance_ratio * model.bounds().diagonal(),
                           normals.size() == at_truth.size() ? normals : fi::Points(),
                           config.facing_tolerance_deg);
  std::vector<double> errors;
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < map.size(); ++i) {
    const double e = static_cast<double>(map.deviation[i]) - exact.deviation[i];
    if (std::isfinite(e)) {
      errors.push_back(std::abs(e));
      sum_sq += e * e;
    }
  }
  AddedError added;
  if (errors.empty()) {
    return added;
  }
  std::sort(errors.begin(), errors.end());
  added.rms = std::sqrt(sum_sq / static_cast<double>(errors.size()));
  added.p95 = errors[errors.size() * 95 / 100];
  added.max = errors.back();
  return added;
}

// A spherical cap centred under a random surface point of the view.
fi::SurfaceDefect placeDefect(const fi::Model& model,
                              const fi::SyntheticScan& clean,
                              double radius,
                              std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const std::size_t surface = clean.scan.points.size() - clean.outliers;
  const std::size_t pick = static_cast<std::size_t>(rng() % surface);
  fi::SurfaceDefect defect;
  defect.centre = model.query().closest(clean.T_cad_scan * clean.scan.points[pick]).point;
  defect.radius = radius;
  return defect;
}

struct Tally {
  int cases = 0;
  int registered = 0;  // status ok and the pose right (issue 4's rule)
  int found = 0;
  int failed_verdict = 0;                 // verdict FAIL
  int false_regions = 0;                  // regions not at the defect
  int split = 0;                          // defects found as more than one region
  std::vector<double> moved;              // scan points the defect moved
  std::vector<double> peak_error_sigmas;  // found: (peak − depth) / σ
};

bool rightPose(const fi::InspectionResult& result,
               const Eigen::Isometry3d& truth,
               const fi::Scan& scan,
               double diagonal) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : scan.points) {
    centroid += p / static_cast<double>(scan.points.size());
  }
  return result.registration == fi::RegistrationStatus::kOk &&
         fi::bench::rotationErrorDeg(result.T_cad_scan, truth) < 2.0 &&
         (result.T_cad_scan * centroid - truth * centroid).norm() < 0.01 * diagonal;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!parse(argc, argv, &options)) {
    std::fprintf(stderr,
                 "usage: detection_eval --cad FILE [--cad-scale S] [--noise R] [--band K] "
                 "[--cases N] [--first-seed N] [--depths D,D,...] [--radii R,R,...] "
                 "[--partial] [--points N] [--bumps]\n");
    return 2;
  }
  const fi::ModelLoadResult loaded = fi::loadModel(options.cad, options.cad_scale, "eval");
  if (!loaded.status.ok()) {
    std::fprintf(stderr, "detection_eval: %s\n", loaded.status.message.c_str());
    return 2;
  }
  const fi::Model& model = *loaded.model;
  const double diagonal = model.bounds().diagonal();
  const double sigma = options.scan.noise_ratio * diagonal;
  const double band = options.band_sigmas * sigma;
  fi::PipelineConfig config;
  config.tolerance.upper = band;
  config.tolerance.lower = -band;
  const double sign = options.bumps ? 1.0 : -1.0;
  std::printf("# %s: L = %.4f m, σ = %.4g mm, band ±%.4g mm (%.3g σ), %s views, %s\n",
              options.cad.c_str(),
              diagonal,
              sigma * 1e3,
              band * 1e3,
              options.band_sigmas,
              options.scan.partial ? "partial" : "full",
              options.bumps ? "bumps" : "dents");

  Tally clean_tally;
  std::vector<double> added_rms, added_p95, added_max;
  std::map<std::pair<std::size_t, std::size_t>, Tally> tallies;  // (radius, depth) index
  for (int c = 0; c < options.cases; ++c) {
    fi::SyntheticScanConfig scan_config = options.scan;
    scan_config.seed = options.first_seed + static_cast<std::uint64_t>(c);
    const fi::SyntheticScan clean = fi::makeSyntheticScan(model.query(), scan_config);
    if (!clean.status.ok()) {
      std::fprintf(stderr, "detection_eval: %s\n", clean.status.message.c_str());
      return 2;
    }
    const fi::InspectionResult reference = fi::inspect(model, clean.scan, config);
    const bool right = rightPose(reference, clean.T_cad_scan, clean.scan, diagonal);
    ++clean_tally.cases;
    clean_tally.registered += right ? 1 : 0;
    clean_tally.failed_verdict += reference.verdict == fi::Verdict::kFail ? 1 : 0;
    clean_tally.false_regions += static_cast<int>(reference.defects.size());
    std::printf("seed %3llu clean: %-9s %s, %zu regions",
                static_cast<unsigned long long>(scan_config.seed),
                fi::toString(reference.registration),
                fi::toString(reference.verdict),
                reference.defects.size());
    if (right) {
      const AddedError added =
          registrationError(model, reference, clean.scan, clean.T_cad_scan, config.deviation);
      added_rms.push_back(added.rms / sigma);
      added_p95.push_back(added.p95 / sigma);
      added_max.push_back(added.max / sigma);
      std::printf("; registration adds RMS %.3g µm, p95 %.3g µm, max %.3g µm",
                  added.rms * 1e6,
                  added.p95 * 1e6,
                  added.max * 1e6);
    }
    std::printf("\n");
    for (std::size_t r = 0; r < options.radii.size(); ++r) {
      fi::SurfaceDefect defect =
          placeDefect(model, clean, options.radii[r] * diagonal, scan_config.seed);
      for (std::size_t d = 0; d < options.depths.size(); ++d) {
        defect.depth = sign * options.depths[d] * band;
        fi::SyntheticScan dented = clean;
        const std::size_t moved = fi::pressDefect(model.query(), defect, &dented);
        const fi::InspectionResult result = fi::inspect(model, dented.scan, config);
        Tally& tally = tallies[{r, d}];
        ++tally.cases;
        tally.moved.push_back(static_cast<double>(moved));
        const bool registered = rightPose(result, dented.T_cad_scan, dented.scan, diagonal);
        tally.registered += registered ? 1 : 0;
        tally.failed_verdict += result.verdict == fi::Verdict::kFail ? 1 : 0;
        const fi::DefectRegion* found = nullptr;  // the largest |peak| of the defect's regions
        int pieces = 0;
        for (const auto& region : result.defects) {
          const bool here = region.sign == static_cast<int>(sign) &&
                            (region.centroid - defect.centre).norm() < defect.radius;
          pieces += here ? 1 : 0;
          tally.false_regions += here ? 0 : 1;
          found = here && found == nullptr ? &region : found;
        }
        tally.split += pieces > 1 ? 1 : 0;
        if (found != nullptr) {
          ++tally.found;
          tally.peak_error_sigmas.push_back((found->peak - defect.depth) / sigma);
        }
        std::printf("  r %6.3g mm depth %5.2f band (%8.4g mm), %5zu points moved: %-9s %-13s",
                    defect.radius * 1e3,
                    options.depths[d],
                    defect.depth * 1e3,
                    moved,
                    fi::toString(result.registration),
                    fi::toString(result.verdict));
        if (found != nullptr) {
          std::printf(" found, peak %.4g mm at %.3g mm, %zu points",
                      found->peak * 1e3,
                      (found->centroid - defect.centre).norm() * 1e3,
                      found->points);
        } else {
          std::printf(" not found");
        }
        std::printf(", %zu regions\n", result.defects.size());
      }
    }
  }

  std::printf(
      "\n| radius [mm] | points in it, median | depth [× band] | right pose | found | in pieces | "
      "FAIL | false regions | peak − depth, median [σ] |\n|---|---|---|---|---|---|---|---|---|\n");
  std::printf("| clean | – | – | %d/%d | – | – | %d/%d | %d | – |\n",
              clean_tally.registered,
              clean_tally.cases,
              clean_tally.failed_verdict,
              clean_tally.cases,
              clean_tally.false_regions);
  for (const auto& [key, tally] : tallies) {
    std::printf("| %.3g | %.0f | %.2f | %d/%d | %d/%d | %d | %d/%d | %d | %.2f |\n",
                options.radii[key.first] * diagonal * 1e3,
                median(tally.moved),
                options.depths[key.second],
                tally.registered,
                tally.cases,
                tally.found,
                tally.cases,
                tally.split,
                tally.failed_verdict,
                tally.cases,
                tally.false_regions,
                median(tally.peak_error_sigmas));
  }
  std::printf(
      "\n# error the registration adds to the deviations of the clean scans (right poses, "
      "%zu): median over scans of RMS %.3f σ, p95 %.3f σ, max %.3f σ\n",
      added_rms.size(),
      median(added_rms),
      median(added_p95),
      median(added_max));
  return 0;
}
