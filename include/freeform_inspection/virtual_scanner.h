// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "freeform_inspection/mesh_query.h"
#include "freeform_inspection/surface_defect.h"
#include "freeform_inspection/types.h"

/// @file virtual_scanner.h
/// A virtual range sensor: ray casts the CAD, placed at a known or random pose, like a
/// structured-light camera (pinhole) or a laser line scanner (a fan of rays swept along a line),
/// and delivers an organized scan (one point per pixel, NaN where nothing was measured) with its
/// ground truth. Sensor effects: range noise along the ray, random dropouts, no return at grazing
/// incidence, outliers, and dents or bumps injected on the CAD surface.
///
/// Sensor frame (the scan's frame): origin at the optical centre, +z along the optical axis, +x
/// to the right of the image (increasing column), +y down (increasing row), like a ROS camera
/// optical frame. A laser line scanner's fan lies in its x–z plane and is swept along +y.

namespace freeform_inspection {

/// How the rays are laid out.
enum class ScannerType {
  kCamera,      ///< pinhole: all rays from the origin, one per pixel
  kLineScanner  ///< one fan of `width` rays per row; rows are profiles taken `height` times
                ///< while the sensor moves along +y by `sweep_length` in total
};

/// The sensor, the part's pose and the effects. Every field has a default that gives a clean
/// VGA structured-light scan of a part at a random pose.
struct VirtualScannerConfig {
  ScannerType type = ScannerType::kCamera;  ///< pinhole camera or laser line scanner
  int width = 640;                          ///< [pixels] columns (line scanner: rays per profile)
  int height = 480;                         ///< [pixels] rows (line scanner: profiles)
  double horizontal_fov_deg = 60.0;  ///< [deg] full horizontal field of view (line: fan angle)
  double min_range = 0.05;           ///< [m] no return closer than this along the ray
  double max_range = 5.0;            ///< [m] no return farther than this along the ray
  /// [m] line scanner: distance moved from the first profile to the last; 0 = the fan's width
  /// at the depth of the part's bounding-box centre (the part then fills the sweep as much as
  /// it fills the fan)
  double sweep_length = 0.0;

  /// true: a uniformly random rotation, and the part's bounding-box centre on the optical axis
  /// at the working distance where its bounding sphere spans `fill_ratio` of the image
  bool random_pose = true;
  /// The part's pose in the sensor frame (CAD → sensor, metres) when `random_pose` is false.
  Eigen::Isometry3d T_sensor_cad = Eigen::Isometry3d::Identity();
  /// random pose: diameter of the part's bounding sphere (the CAD diagonal L) as a share of the
  /// image's smaller side (line scanner: of the profile's width) [-]; above 1 the part
  /// overflows the image (partial views)
  double fill_ratio = 0.6;

  double noise_sigma = 0.0;          ///< [m] σ of Gaussian range noise along the ray
  double noise_ratio = 0.0;          ///< the same σ as a share of L; set at most one of the two
  double dropout_probability = 0.0;  ///< chance that a pixel with a return loses it [0, 1]
  double max_incidence_deg = 80.0;   ///< [deg] no return where the ray meets the surface at a
                                     ///< larger angle to its normal (grazing); 90 = off
  /// share of all pixels that return a spurious range instead [0, 1]: uniform along the
  /// pixel's ray within the depth of the part's bounding sphere (clipped to the sensor's range)
  double outlier_fraction = 0.0;
  /// dents and bumps in the CAD frame [m]: each hit point moves along the CAD's outward normal
  /// by the sum of their defectDisplacement(), before the noise
  std::vector<SurfaceDefect> defects;
  /// true: the part rests on a flat support (a table) that the sensor sees wherever the part
  /// does not hide it, measured with the same noise and dropouts. Its plane touches the part's
  /// far side; its normal faces the sensor, turned from the optical axis by a random angle
  /// (from the seed) of at most `support_tilt_deg`. It reaches the edges of the image.
  bool support = false;
  double support_tilt_deg = 30.0;  ///< [deg] in [0, 60]
  std::uint64_t seed = 1;  ///< same seed, same config → bit-identical scan, any thread count
};

/// @brief Checks every field of the configuration.
/// @return one message per invalid field, naming it and its value; empty when valid.
std::vector<std::string> validate(const VirtualScannerConfig& config);

/// What became of one pixel.
enum class PixelOutcome : std::uint8_t {
  kMiss,        ///< the ray hits nothing (NaN)
  kOutOfRange,  ///< first hit closer than min_range or farther than max_range (NaN)
  kGrazing,     ///< incidence above max_incidence_deg, or a back face (NaN)
  kDropout,     ///< a return lost at random (NaN)
  kValid,       ///< a measured surface point (finite)
  kOutlier,     ///< a spurious range (finite, not on the surface)
  kSupport,     ///< a measured point of the support the part rests on (finite, not the part)
};

/// How many pixels ended in each outcome; they add up to width · height.
struct VirtualScanCounts {
  std::size_t valid = 0;         ///< finite points on the (defect-displaced, noisy) surface
  std::size_t outliers = 0;      ///< finite spurious points
  std::size_t support = 0;       ///< finite points of the support (VirtualScannerConfig::support)
  std::size_t misses = 0;        ///< rays that hit nothing
  std::size_t out_of_range = 0;  ///< hits outside [min_range, max_range]
  std::size_t grazing = 0;       ///< hits beyond max_incidence_deg or on back faces
  std::size_t dropouts = 0;      ///< returns removed at random
  std::size_t displaced = 0;     ///< valid points moved by a defect (displacement ≠ 0)
};

/// A virtual scan and its truth.
struct VirtualScan {
  Status status;  ///< kInvalidInput (bad config or CAD), kDegenerateInput (no pixel sees the part)
  /// organized width × height, row-major, sensor frame [m], NaN where nothing was measured; no
  /// normals, no faces
  Scan scan;
  Eigen::Isometry3d T_cad_scan = Eigen::Isometry3d::Identity();  ///< truth: scan → CAD
  std::vector<PixelOutcome> pixels;  ///< per pixel, row-major (finite = kValid or kOutlier)
  VirtualScanCounts counts;          ///< pixels per outcome
  double noise_sigma = 0.0;          ///< [m] the range noise σ applied
  double working_distance = 0.0;     ///< [m] sensor origin to the part's bounding-box centre
  double sweep_length = 0.0;         ///< [m] line scanner: the sweep used (0 for a camera)
  /// The support's plane in the sensor frame, n·x = d with n unit and facing the sensor (zero
  /// without a support).
  Eigen::Vector4d support_plane = Eigen::Vector4d::Zero();
  std::vector<std::string> warnings;  ///< e.g. the part reaches outside the sensor's range
};

/// @brief Scans the CAD with the virtual sensor. Each pixel's ray is cast on the exact CAD
/// triangles; the first hit, if within range and not grazing, is displaced by the defects, then
/// moved along the ray by the noise; dropouts and outliers are drawn per pixel. Every pixel has
/// its own random stream derived from the seed and its index, so the scan does not depend on the
/// thread count or on the order of the pixels. The random pose comes from the seed alone.
/// @param cad the CAD mesh in its own frame [m]
/// @return status kInvalidInput with every problem listed for a config that does not validate()
/// or an unusable CAD, kDegenerateInput when not a single pixel measured the part.
VirtualScan makeVirtualScan(const MeshQuery& cad, const VirtualScannerConfig& config);

}  // namespace freeform_inspection
