// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/virtual_scanner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
constexpr std::size_t kMaxPixels = 50000000;  // 50 Mpixel ≈ 1.3 GB of points: a typo, not a sensor
constexpr double kRotationTolerance = 1e-6;   // T_sensor_cad must be rigid to this (R^T R − I)

// SplitMix64's finalizer: a bijection of 64-bit words with full avalanche, so neighbouring pixel
// indices get unrelated streams.
std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// One pixel's random stream (SplitMix64). Seeding a Mersenne twister per pixel would cost more
// than the ray cast; a shared generator would make the scan depend on the thread schedule.
class PixelRandom {
 public:
  PixelRandom(std::uint64_t seed, std::uint64_t pixel) : state_(mix64(mix64(seed) ^ pixel)) {}

  double uniform() {  // [0, 1), 53 bits
    state_ += 0x9E3779B97F4A7C15ULL;
    return static_cast<double>(mix64(state_) >> 11) * (1.0 / 9007199254740992.0);
  }

  double gaussian() {  // Box-Muller; 1 − u keeps the logarithm finite
    const double radius = std::sqrt(-2.0 * std::log(1.0 - uniform()));
    return radius * std::cos(2.0 * kPi * uniform());
  }

 private:
  std::uint64_t state_;
};

// Uniform on SO(3): a normalized 4-D isotropic Gaussian is a uniform unit quaternion (the same
// construction as synthetic_scan.cpp, on mt19937_64's raw output so any library gives the same).
Eigen::Quaterniond randomRotation(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto gaussian = [&rng] {
    const auto uniform = [&rng] {
      return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0);
    };
    const double radius = std::sqrt(-2.0 * std::log(1.0 - uniform()));
    return radius * std::cos(2.0 * kPi * uniform());
  };
  Eigen::Vector4d v;
  do {
    v = Eigen::Vector4d(gaussian(), gaussian(), gaussian(), gaussian());
  } while (!(v.norm() > 1e-9));
  v.normalize();
  return Eigen::Quaterniond(v[0], v[1], v[2], v[3]);
}

std::string text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void checkRange(std::vector<std::string>& errors,
                const char* name,
                double value,
                double low,
                double high,
                bool low_open) {
  const bool ok = std::isfinite(value) && (low_open ? value > low : value >= low) && value <= high;
  if (ok) {
    return;
  }
  const std::string prefix = std::string("virtual_scanner.") + name + " = " + text(value);
  if (std::isinf(high)) {
    errors.push_back(prefix + " must be a finite value " + (low_open ? "> " : ">= ") + text(low));
  } else {
    errors.push_back(prefix + " must be in " + (low_open ? "(" : "[") + text(low) + ", " +
                     text(high) + "]");
  }
}

void validateSensor(const VirtualScannerConfig& config, std::vector<std::string>& errors) {
  if (config.width < 2 || config.height < 2) {
    errors.push_back("virtual_scanner.width × height = " + std::to_string(config.width) + " × " +
                     std::to_string(config.height) + ": both must be at least 2");
  } else if (static_cast<std::size_t>(config.width) * static_cast<std::size_t>(config.height) >
             kMaxPixels) {
    errors.push_back("virtual_scanner.width × height = " + std::to_string(config.width) + " × " +
                     std::to_string(config.height) + " exceeds " + std::to_string(kMaxPixels) +
                     " pixels");
  }
  if (!(config.horizontal_fov_deg > 0.0 && config.horizontal_fov_deg < 180.0)) {
    errors.push_back("virtual_scanner.horizontal_fov_deg = " + text(config.horizontal_fov_deg) +
                     " must be in (0, 180)");
  }
  if (!(config.min_range >= 0.0 && config.min_range < config.max_range &&
        std::isfinite(config.max_range))) {
    errors.push_back("virtual_scanner.min_range = " + text(config.min_range) + " and max_range = " +
                     text(config.max_range) + " must satisfy 0 <= min_range < max_range < inf");
  }
  if (!(std::isfinite(config.sweep_length) && config.sweep_length >= 0.0)) {
    errors.push_back("virtual_scanner.sweep_length = " + text(config.sweep_length) +
                     " must be a finite value >= 0 (0 = automatic)");
  }
}

void validatePose(const VirtualScannerConfig& config, std::vector<std::string>& errors) {
  if (config.random_pose) {
    if (!(std::isfinite(config.fill_ratio) && config.fill_ratio > 0.0)) {
      errors.push_back("virtual_scanner.fill_ratio = " + text(config.fill_ratio) +
                       " must be a finite value > 0");
    }
    return;
  }
  if (!isRigidTransform(config.T_sensor_cad.matrix(), kRotationTolerance)) {
    errors.push_back(
        "virtual_scanner.T_sensor_cad is not a finite rigid transform (rotation not orthonormal "
        "with determinant +1)");
  }
}

void validateEffects(const VirtualScannerConfig& config, std::vector<std::string>& errors) {
  const double inf = std::numeric_limits<double>::infinity();
  checkRange(errors, "noise_sigma", config.noise_sigma, 0.0, inf, false);
  checkRange(errors, "noise_ratio", config.noise_ratio, 0.0, inf, false);
  if (config.noise_sigma > 0.0 && config.noise_ratio > 0.0) {
    errors.push_back("virtual_scanner: set noise_sigma (" + text(config.noise_sigma) +
                     " m) or noise_ratio (" + text(config.noise_ratio) + " × L), not both");
  }
  checkRange(errors, "dropout_probability", config.dropout_probability, 0.0, 1.0, false);
  checkRange(errors, "outlier_fraction", config.outlier_fraction, 0.0, 1.0, false);
  checkRange(errors, "max_incidence_deg", config.max_incidence_deg, 0.0, 90.0, true);
  checkRange(errors, "support_tilt_deg", config.support_tilt_deg, 0.0, 60.0, false);
  for (std::size_t i = 0; i < config.defects.size(); ++i) {
    const SurfaceDefect& d = config.defects[i];
    const bool ok = d.centre.allFinite() && std::isfinite(d.radius) && d.radius > 0.0 &&
                    std::isfinite(d.depth) && std::abs(d.depth) <= d.radius;
    if (!ok) {
      errors.push_back("virtual_scanner.defects[" + std::to_string(i) +
                       "]: radius = " + text(d.radius) + ", depth = " + text(d.depth) +
                       ": needs a finite centre, radius > 0 and |depth| <= radius");
    }
  }
}

// Everything derived once per scan: intrinsics, pose, σ, the sweep.
struct Setup {
  Eigen::Isometry3d T_sensor_cad = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_cad_sensor = Eigen::Isometry3d::Identity();
  double focal = 1.0;  // [pixels] fx = fy (square pixels)
  double cx = 0.0;     // [pixels] principal point: the image centre
  double cy = 0.0;
  double line_step = 0.0;  // [m] line scanner: sensor motion between profiles
  double sigma = 0.0;      // [m]
  double cos_max_incidence = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // part's box centre, sensor frame [m]
  double radius = 0.0;  // [m] the part's bounding sphere (half the box diagonal)
  bool support = false;
  Eigen::Vector3d support_normal = Eigen::Vector3d::Zero();  // sensor frame, unit, to the sensor
  double support_offset = 0.0;                               // [m] n·x on the plane
};

// The support's plane: its normal turned from −z (towards the sensor) by a random tilt about a
// random axis in the image plane, its offset the least n·v over the part's vertices, so the
// plane touches the part's far side and the whole part lies on the sensor's side of it.
void placeSupport(const VirtualScannerConfig& config, const Points& vertices, Setup* setup) {
  // A stream of its own (the index no pixel has), so the pixels' draws stay as they were.
  PixelRandom random(config.seed, std::numeric_limits<std::uint64_t>::max());
  const double tilt = config.support_tilt_deg * kDegToRad * random.uniform();
  const double azimuth = 2.0 * kPi * random.uniform();
  const Eigen::Vector3d axis(std::cos(azimuth), std::sin(azimuth), 0.0);
  setup->support = true;
  setup->support_normal = Eigen::AngleAxisd(tilt, axis) * Eigen::Vector3d(0.0, 0.0, -1.0);
  setup->support_offset = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : vertices) {
    setup->support_offset =
        std::min(setup->support_offset, setup->support_normal.dot(setup->T_sensor_cad * v));
  }
}

// Random pose: the working distance D where the bounding sphere's projected radius r·f/D is
// fill_ratio × half the image's smaller side (the profile's width for a line scanner).
Eigen::Isometry3d randomPose(const VirtualScannerConfig& config,
                             const BoundingBox& box,
                             double focal) {
  const int side =
      config.type == ScannerType::kCamera ? std::min(config.width, config.height) : config.width;
  const double distance = box.diagonal() * focal / (config.fill_ratio * side);
  Eigen::Isometry3d T_sensor_cad = Eigen::Isometry3d::Identity();
  T_sensor_cad.linear() = randomRotation(config.seed).toRotationMatrix();
  const Eigen::Vector3d centre = 0.5 * (box.min + box.max);
  T_sensor_cad.translation() = Eigen::Vector3d(0.0, 0.0, distance) - T_sensor_cad.linear() * centre;
  return T_sensor_cad;
}

Setup makeSetup(const VirtualScannerConfig& config, const BoundingBox& box, double* sweep) {
  Setup setup;
  setup.focal = 0.5 * config.width / std::tan(0.5 * config.horizontal_fov_deg * kDegToRad);
  setup.cx = 0.5 * (config.width - 1);
  setup.cy = 0.5 * (config.height - 1);
  setup.T_sensor_cad =
      config.random_pose ? randomPose(config, box, setup.focal) : config.T_sensor_cad;
  setup.T_cad_sensor = setup.T_sensor_cad.inverse();
  setup.sigma = config.noise_sigma + config.noise_ratio * box.diagonal();  // one of them is 0
  setup.cos_max_incidence = std::cos(config.max_incidence_deg * kDegToRad);
  setup.centre = setup.T_sensor_cad * (0.5 * (box.min + box.max));
  setup.radius = 0.5 * box.diagonal();
  *sweep = 0.0;
  if (config.type == ScannerType::kLineScanner) {
    // Automatic: the fan's width at the part's centre, width / focal per unit depth.
    *sweep = config.sweep_length > 0.0
                 ? config.sweep_length
                 : std::max(0.0, setup.centre.z()) * config.width / setup.focal;
    setup.line_step = *sweep / (config.height - 1);
  }
  return setup;
}

struct Ray {
  Eigen::Vector3d origin;     // sensor frame [m]
  Eigen::Vector3d direction;  // unit
};

Ray pixelRay(const VirtualScannerConfig& config, const Setup& setup, int row, int column) {
  const double x = (column - setup.cx) / setup.focal;
  if (config.type == ScannerType::kCamera) {
    const double y = (row - setup.cy) / setup.focal;
    return {Eigen::Vector3d::Zero(), Eigen::Vector3d(x, y, 1.0).normalized()};
  }
  const double offset = (row - setup.cy) * setup.line_step;  // sweep centred on the frame
  return {Eigen::Vector3d(0.0, offset, 0.0), Eigen::Vector3d(x, 0.0, 1.0).normalized()};
}

struct PixelSample {
  PixelOutcome outcome = PixelOutcome::kMiss;
  bool displaced = false;
  Eigen::Vector3d point = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
};

// A spurious return: uniform along the ray over the depth of the part's bounding sphere, within
// the sensor's range (the whole range when the part lies outside it).
Eigen::Vector3d outlierPoint(const VirtualScannerConfig& config,
                             const Setup& setup,
                             const Ray& ray,
                             double u) {
  const double to_centre = (setup.centre - ray.origin).norm();
  double low = std::max(config.min_range, to_centre - setup.radius);
  double high = std::min(config.max_range, to_centre + setup.radius);
  if (!(low < high)) {
    low = config.min_range;
    high = config.max_range;
  }
  return ray.origin + (low + (high - low) * u) * ray.direction;
}

// A ray that misses the part meets the support behind it (or nothing, when it runs parallel to
// or away from the support's plane), with the part's range, incidence, dropout and noise rules.
PixelSample supportPixel(const VirtualScannerConfig& config,
                         const Setup& setup,
                         const Ray& ray,
                         double u_dropout,
                         double noise) {
  PixelSample sample;
  const double towards = setup.support_normal.dot(ray.direction);
  if (!(towards < 0.0)) {
    return sample;  // kMiss
  }
  const double t = (setup.support_offset - setup.support_normal.dot(ray.origin)) / towards;
  if (!(t > 0.0)) {
    return sample;  // the sensor is behind the support: a configuration no sensor has
  }
  if (t < config.min_range || t > config.max_range) {
    sample.outcome = PixelOutcome::kOutOfRange;
    return sample;
  }
  if (-towards < setup.cos_max_incidence) {
    sample.outcome = PixelOutcome::kGrazing;
    return sample;
  }
  if (u_dropout < config.dropout_probability) {
    sample.outcome = PixelOutcome::kDropout;
    return sample;
  }
  sample.outcome = PixelOutcome::kSupport;
  sample.point = ray.origin + (t + setup.sigma * noise) * ray.direction;
  return sample;
}

// One pixel. Its random numbers are drawn up front, in a fixed order and number, so each effect's
// pattern stays the same when another effect is switched on or off.
PixelSample scanPixel(const MeshQuery& cad,
                      const VirtualScannerConfig& config,
                      const Setup& setup,
                      int row,
                      int column) {
  const auto index = static_cast<std::uint64_t>(row) * static_cast<std::uint64_t>(config.width) +
                     static_cast<std::uint64_t>(column);
  PixelRandom random(config.seed, index);
  const double u_outlier = random.uniform();
  const double u_outlier_range = random.uniform();
  const double u_dropout = random.uniform();
  const double noise = random.gaussian();

  PixelSample sample;
  const Ray ray = pixelRay(config, setup, row, column);
  if (u_outlier < config.outlier_fraction) {
    sample.outcome = PixelOutcome::kOutlier;
    sample.point = outlierPoint(config, setup, ray, u_outlier_range);
    return sample;
  }
  // Cast in the CAD frame, where the defects and the normals live.
  const Eigen::Vector3d direction = setup.T_cad_sensor.linear() * ray.direction;
  const RayHit hit = cad.castRay(setup.T_cad_sensor * ray.origin, direction);
  if (!hit.hit) {
    return setup.support ? supportPixel(config, setup, ray, u_dropout, noise) : sample;
  }
  if (hit.t < config.min_range || hit.t > config.max_range) {
    sample.outcome = PixelOutcome::kOutOfRange;
    return sample;
  }
  // Back faces (cos ≤ 0) never return: the ray met the part from inside or an open edge.
  const double cos_incidence = -direction.dot(hit.normal);
  if (!(cos_incidence > 0.0 && cos_incidence >= setup.cos_max_incidence)) {
    sample.outcome = PixelOutcome::kGrazing;
    return sample;
  }
  if (u_dropout < config.dropout_probability) {
    sample.outcome = PixelOutcome::kDropout;
    return sample;
  }
  double displacement = 0.0;
  for (const SurfaceDefect& defect : config.defects) {
    displacement += defectDisplacement(defect, hit.point);
  }
  // Along the normal, so the deviation is the defect's own; the point leaves its pixel's ray by
  // at most |displacement|·sin(incidence), well under a pixel for defects of inspection size.
  const Eigen::Vector3d on_part =
      hit.point + displacement * hit.normal + setup.sigma * noise * direction;
  sample.outcome = PixelOutcome::kValid;
  sample.displaced = displacement != 0.0;
  sample.point = setup.T_sensor_cad * on_part;
  return sample;
}

void count(const PixelSample& sample, VirtualScanCounts& counts) {
  switch (sample.outcome) {
    case PixelOutcome::kMiss:
      ++counts.misses;
      break;
    case PixelOutcome::kOutOfRange:
      ++counts.out_of_range;
      break;
    case PixelOutcome::kGrazing:
      ++counts.grazing;
      break;
    case PixelOutcome::kDropout:
      ++counts.dropouts;
      break;
    case PixelOutcome::kValid:
      ++counts.valid;
      counts.displaced += sample.displaced ? 1 : 0;
      break;
    case PixelOutcome::kOutlier:
      ++counts.outliers;
      break;
    case PixelOutcome::kSupport:
      ++counts.support;
      break;
  }
}

std::vector<std::string> rangeWarnings(const VirtualScannerConfig& config, const Setup& setup) {
  const double distance = setup.centre.norm();
  if (distance - setup.radius >= config.min_range && distance + setup.radius <= config.max_range) {
    return {};
  }
  return {"the part's bounding sphere spans " + text(distance - setup.radius) + " to " +
          text(distance + setup.radius) + " m from the sensor, outside its range [" +
          text(config.min_range) + ", " + text(config.max_range) +
          "] m: surfaces out of range are not measured"};
}

}  // namespace

std::vector<std::string> validate(const VirtualScannerConfig& config) {
  std::vector<std::string> errors;
  validateSensor(config, errors);
  validatePose(config, errors);
  validateEffects(config, errors);
  return errors;
}

VirtualScan makeVirtualScan(const MeshQuery& cad, const VirtualScannerConfig& config) {
  VirtualScan result;
  if (!cad.status().ok()) {
    result.status = Status::failure(StatusCode::kInvalidInput,
                                    "virtual scanner: unusable CAD: " + cad.status().message);
    return result;
  }
  const std::vector<std::string> errors = validate(config);
  if (!errors.empty()) {
    result.status =
        Status::failure(StatusCode::kInvalidInput, "virtual scanner: " + joinMessages(errors));
    return result;
  }
  const BoundingBox box = computeBoundingBox(cad.mesh().vertices);
  Setup setup = makeSetup(config, box, &result.sweep_length);
  if (config.support) {
    placeSupport(config, cad.mesh().vertices, &setup);
    result.support_plane << setup.support_normal, setup.support_offset;
  }

  const int width = config.width;
  const auto pixels = static_cast<long long>(width) * config.height;
  std::vector<PixelSample> samples(static_cast<std::size_t>(pixels));
  // Each pixel owns its random stream and its slot: the output is the same for any schedule.
#pragma omp parallel for schedule(dynamic, 256)
  for (long long i = 0; i < pixels; ++i) {
    samples[static_cast<std::size_t>(i)] =
        scanPixel(cad, config, setup, static_cast<int>(i / width), static_cast<int>(i % width));
  }

  result.scan.width = width;
  result.scan.height = config.height;
  result.scan.points.reserve(samples.size());
  result.pixels.reserve(samples.size());
  for (const PixelSample& sample : samples) {
    result.scan.points.push_back(sample.point);
    result.pixels.push_back(sample.outcome);
    count(sample, result.counts);
  }
  result.T_cad_scan = setup.T_cad_sensor;
  result.noise_sigma = setup.sigma;
  result.working_distance = setup.centre.norm();
  result.warnings = rangeWarnings(config, setup);
  if (result.counts.valid == 0) {
    result.status = Status::failure(
        StatusCode::kDegenerateInput,
        "virtual scanner: no pixel measured the part (" + std::to_string(result.counts.misses) +
            " misses, " + std::to_string(result.counts.out_of_range) + " out of range, " +
            std::to_string(result.counts.grazing) + " grazing, " +
            std::to_string(result.counts.dropouts) + " dropouts)");
  }
  return result;
}

}  // namespace freeform_inspection
