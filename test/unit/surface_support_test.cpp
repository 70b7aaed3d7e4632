// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "freeform_inspection/surface_support.h"

#include <random>

#include "test_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/descriptor.h"
#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace {

constexpr unsigned kSeed = 20261122;
const Eigen::Vector3d kHalf(0.05, 0.03, 0.02);  // a 100 × 60 × 40 mm box

struct BoxScan {
  TriangleMesh cad = test::makeBox(kHalf);
  Points points;
  DescriptorResult descriptors;
};

// The box's surface sampled at random, plus `outliers` × as many points uniform in a box 20 %
// larger; described on the surface graph the pipeline uses.
BoxScan boxScan(double outliers) {
  BoxScan scan;
  scan.points = test::sampleBoxSurface(kHalf, 20000, kSeed);
  std::mt19937 rng(kSeed + 1);
  std::uniform_real_distribution<double> unit(-1.2, 1.2);
  const auto extra = static_cast<int>(outliers * 20000);
  for (int i = 0; i < extra; ++i) {
    const double x = unit(rng) * kHalf.x();
    const double y = unit(rng) * kHalf.y();
    scan.points.emplace_back(x, y, unit(rng) * kHalf.z());
  }
  const auto radii = kernelRadii(2.0 * kHalf.norm(), DescriptorConfig());
  scan.descriptors = computeDescriptors(scan.points, {}, {}, radii, DescriptorConfig());
  return scan;
}

constexpr double kBand = 0.0005;  // 0.5 mm: the inlier distance of a clean scan of this size

// The share of `scan`'s surface on its own box at `pose`.
double shareAt(const BoxScan& scan, const Eigen::Isometry3d& pose) {
  EXPECT_TRUE(scan.descriptors.status.ok()) << scan.descriptors.status.message;
  const MeshQuery cad(scan.cad);
  return surfaceOnCad(scan.descriptors.graph, scan.points, cad, pose, kBand, 1500);
}

TEST(SurfaceSupport, RightPoseOfACleanScanPutsAllOfItsSurfaceOnTheCad) {
  EXPECT_GT(shareAt(boxScan(0.0), Eigen::Isometry3d::Identity()), 0.999);
}

TEST(SurfaceSupport, ScatteredOutliersAreNotSurface) {
  // 20 % outliers: ICP fitness would be 0.83 at the right pose. Only the outliers close enough
  // to the faces to link to them count (measured 0.953), far above a slid pose's 0.71.
  EXPECT_GT(shareAt(boxScan(0.2), Eigen::Isometry3d::Identity()), 0.93) << "seed " << kSeed;
}

TEST(SurfaceSupport, SlidPoseLeavesTheFacesAcrossTheSlideOffTheCad) {
  const BoxScan scan = boxScan(0.0);
  Eigen::Isometry3d slid = Eigen::Isometry3d::Identity();
  slid.translation() = Eigen::Vector3d(0.005, 0.0, 0.0);
  // The ±x faces (19 % of the area) are 5 mm off and a 5 mm strip of the others hangs over the
  // edge (5 % more): about three quarters stay on the CAD (measured 0.709).
  const double share = shareAt(scan, slid);
  EXPECT_GT(share, 0.65);
  EXPECT_LT(share, 0.78);
  // A half-turn about z maps the box onto itself: all of it is supported again.
  Eigen::Isometry3d turned = Eigen::Isometry3d::Identity();
  turned.linear() = Eigen::AngleAxisd(3.14159265358979323846, Eigen::Vector3d::UnitZ()).matrix();
  EXPECT_GT(shareAt(scan, turned), 0.999);
}

TEST(SurfaceSupport, NothingToMeasureIsFullSupportNotACrash) {
  const BoxScan scan = boxScan(0.0);
  const MeshQuery cad(scan.cad);
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  EXPECT_EQ(surfaceOnCad(SurfaceGraph(), {}, cad, identity, kBand, 1500), 1.0);
  EXPECT_EQ(surfaceOnCad(scan.descriptors.graph, {}, cad, identity, kBand, 1500), 1.0);
  EXPECT_EQ(surfaceOnCad(scan.descriptors.graph, scan.points, cad, identity, kBand, 0), 1.0);
}

}  // namespace
}  // namespace freeform_inspection
