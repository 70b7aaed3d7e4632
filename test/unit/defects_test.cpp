// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// Defect regions on a scanned plane (z = 0 is the nominal surface, so the deviation is z):
// spherical-cap dents and bumps of known place, radius and depth, with and without noise, as
// a mesh and as a cloud.
#include "freeform_inspection/defects.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "analytic_shapes.h"
#include <gtest/gtest.h>

#include "freeform_inspection/regions.h"
#include "freeform_inspection/surface_defect.h"

namespace freeform_inspection {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct PlaneScan {
  Points points;
  Triangles faces;
  std::vector<float> deviation;
};

// A 100 mm square scanned on a 0.5 mm grid, with the defects applied and Gaussian noise.
PlaneScan scanPlane(const std::vector<SurfaceDefect>& defects, double sigma, unsigned seed) {
  const TriangleMesh grid = test::planarGrid(0.1, 200);
  PlaneScan scan{grid.vertices, grid.faces, {}};
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (auto& p : scan.points) {
    for (const auto& d : defects) {
      p.z() += defectDisplacement(d, p);
    }
    if (sigma > 0.0) {
      p.z() += noise(rng);
    }
    scan.deviation.push_back(static_cast<float>(p.z()));
  }
  return scan;
}

ToleranceConfig band(double half_width) {
  ToleranceConfig tolerance;
  tolerance.upper = half_width;
  tolerance.lower = -half_width;
  return tolerance;
}

// Area of the cap's footprint where |displacement| exceeds the band: a disc of radius ρ with
// h − (R − sqrt(R² − ρ²)) = band.
double discAbove(const SurfaceDefect& d, double limit) {
  const double h = std::abs(d.depth);
  const double sphere = (d.radius * d.radius + h * h) / (2.0 * h);
  const double drop = h - limit;  // R − sqrt(R² − ρ²) = drop
  const double rho2 = sphere * sphere - (sphere - drop) * (sphere - drop);
  return kPi * rho2;
}

TEST(Defects, DentOnAMeshIsFoundWithItsPlaceSignPeakAndArea) {
  const SurfaceDefect dent{Eigen::Vector3d(0.012, -0.02, 0.0), 0.01, -0.001};
  const PlaneScan scan = scanPlane({dent}, 0.0, 1);
  const DefectResult result =
      findDefects(scan.points, scan.faces, scan.deviation, band(2e-4), DefectConfig());
  ASSERT_EQ(result.regions.size(), 1u);
  const DefectRegion& region = result.regions.front();
  const double area = discAbove(dent, 2e-4);
  // The centroid of the dented points: on the axis of the dent, below the nominal surface.
  const Eigen::Vector3d offset = region.centroid - dent.centre;
  std::printf(
      "dent: area %.4g mm^2 (analytic %.4g), centroid %.3g mm off-axis, %.3g mm deep, "
      "peak %.4g mm\n",
      region.area * 1e6,
      area * 1e6,
      offset.head<2>().norm() * 1e3,
      offset.z() * 1e3,
      region.peak * 1e3);
  EXPECT_EQ(region.sign, -1);
  EXPECT_LT(offset.head<2>().norm(), 0.1e-3);
  EXPECT_LT(offset.z(), -2e-4);
  EXPECT_GT(offset.z(), -1e-3);
  EXPECT_NEAR(region.peak, -0.001, 0.02 * 0.001);
  EXPECT_NEAR(region.area, area, 0.05 * area);
  EXPECT_LT(region.mean, -2e-4);
  EXPECT_GT(region.mean, -0.001);
  EXPECT_LE(region.bbox_min.x(), dent.centre.x() - 0.005);
  EXPECT_GE(region.bbox_max.x(), dent.centre.x() + 0.005);
  std::size_t members = 0;
  for (const int r : result.point_region) {
    members += r == 0 ? 1 : 0;
  }
  EXPECT_EQ(members, region.points);
}

TEST(Defects, CloudAndMeshGiveTheSameRegions) {
  const std::vector<SurfaceDefect> defects = {{Eigen::Vector3d(-0.02, 0.02, 0.0), 0.008, 6e-4},
                                              {Eigen::Vector3d(0.025, -0.01, 0.0), 0.012, -9e-4}};
  const PlaneScan scan = scanPlane(defects, 2e-5, 3);
  const auto mesh = findDefects(scan.points, scan.faces, scan.deviation, band(2e-4), {});
  const auto cloud = findDefects(scan.points, {}, scan.deviation, band(2e-4), {});
  ASSERT_EQ(mesh.regions.size(), 2u);
  ASSERT_EQ(cloud.regions.size(), 2u);
  // Sorted by |peak|: the dent (0.9 mm) first.
  EXPECT_EQ(mesh.regions[0].sign, -1);
  EXPECT_EQ(mesh.regions[1].sign, 1);
  EXPECT_LT((mesh.regions[0].centroid - defects[1].centre).norm(), 1e-3);
  EXPECT_LT((mesh.regions[1].centroid - defects[0].centre).norm(), 1e-3);
  for (std::size_t r = 0; r < 2; ++r) {
    EXPECT_EQ(cloud.regions[r].points, mesh.regions[r].points);
    EXPECT_NEAR(cloud.regions[r].area, mesh.regions[r].area, 0.05 * mesh.regions[r].area);
    EXPECT_DOUBLE_EQ(cloud.regions[r].peak, mesh.regions[r].peak);
  }
}

TEST(Defects, NoiseAloneGivesNoRegionAtAFourSigmaBand) {
  const double sigma = 5e-5;
  for (const unsigned seed : {1u, 2u, 3u}) {
    const PlaneScan scan = scanPlane({}, sigma, seed);
    std::size_t outside = 0;
    for (const float d : scan.deviation) {
      outside += std::abs(d) > 4.0 * sigma ? 1 : 0;
    }
    const auto mesh = findDefects(scan.points, scan.faces, scan.deviation, band(4 * sigma), {});
    const auto cloud = findDefects(scan.points, {}, scan.deviation, band(4 * sigma), {});
    std::printf("seed %u: %zu of %zu points beyond 4 sigma, %zu / %zu regions\n",
                seed,
                outside,
                scan.points.size(),
                mesh.regions.size(),
                cloud.regions.size());
    EXPECT_GT(outside, 0u);  // the band is crossed, yet by scattered points only
    EXPECT_TRUE(mesh.regions.empty());
    EXPECT_TRUE(cloud.regions.empty());
  }
}

// The same regions in the same order, bit for bit.
void expectSameRegions(const DefectResult& a, const DefectResult& b) {
  ASSERT_EQ(a.regions.size(), b.regions.size());
  for (std::size_t r = 0; r < b.regions.size(); ++r) {
    EXPECT_EQ(a.regions[r].points, b.regions[r].points) << r;
    EXPECT_EQ(a.regions[r].sign, b.regions[r].sign) << r;
    EXPECT_EQ(a.regions[r].peak, b.regions[r].peak) << r;
    EXPECT_EQ(a.regions[r].centroid, b.regions[r].centroid) << r;
    EXPECT_EQ(a.regions[r].area, b.regions[r].area) << r;
  }
}

// A band far below the noise puts most of a cloud out of tolerance; its neighbours then come
// from one table of the whole cloud instead of a kd-tree query per point. The regions must be
// the same: the same cloud with eight in-tolerance copies of itself 10 m away (the spacing,
// each point's nearest neighbours and the areas unchanged) keeps fewer than an eighth of its
// points out of tolerance, so its neighbours are queried point by point.
TEST(Defects, NeighboursFromOneTableOrPerPointGiveTheSameRegions) {
  const std::vector<SurfaceDefect> defects = {{Eigen::Vector3d(-0.02, 0.02, 0.0), 0.008, 6e-4}};
  const PlaneScan scan = scanPlane(defects, 5e-5, 4);
  const ToleranceConfig tolerance = band(3e-5);
  const DefectResult dense = findDefects(scan.points, {}, scan.deviation, tolerance, {});
  Points points = scan.points;
  std::vector<float> deviation = scan.deviation;
  for (int copy = 1; copy <= 8; ++copy) {
    for (const Eigen::Vector3d& p : scan.points) {
      points.push_back(p + Eigen::Vector3d(10.0 * copy, 0.0, 0.0));
      deviation.push_back(0.0F);
    }
  }
  const DefectResult sparse = findDefects(points, {}, deviation, tolerance, {});
  std::size_t outside = 0;
  for (const float d : scan.deviation) {
    outside += std::abs(d) > 3e-5 ? 1 : 0;
  }
  std::printf("%zu of %zu points out of tolerance, %zu regions\n",
              outside,
              scan.points.size(),
              dense.regions.size());
  ASSERT_GT(outside * 8, scan.points.size());  // the table's case
  ASSERT_GE(dense.regions.size(), 1u);
  expectSameRegions(sparse, dense);
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    ASSERT_EQ(sparse.point_region[i], dense.point_region[i]) << i;
  }
}

// The guard bands judge three bands on one scan through one DefectNeighbourhood: its kd-tree,
// spacing and neighbour table, built for the first band that needs them, must give every band
// the regions a call of its own gives, on a mesh and on a cloud, in the per-point case (a band
// above the noise) and the table's (a band far below it), in either order.
TEST(Defects, OneNeighbourhoodForSeveralBandsGivesEachBandItsOwnRegions) {
  const std::vector<SurfaceDefect> defects = {{Eigen::Vector3d(-0.02, 0.02, 0.0), 0.008, 6e-4},
                                              {Eigen::Vector3d(0.02, -0.01, 0.0), 0.006, -4e-4}};
  const PlaneScan scan = scanPlane(defects, 5e-5, 5);
  const std::vector<double> bands = {2e-4, 3e-5, 3e-4, 1e-4};
  for (const bool mesh : {true, false}) {
    SCOPED_TRACE(mesh ? "mesh" : "cloud");
    const Triangles faces = mesh ? scan.faces : Triangles();
    DefectNeighbourhood surface(scan.points, faces);
    for (const double half_width : bands) {
      SCOPED_TRACE(half_width);
      const DefectResult alone =
          findDefects(scan.points, faces, scan.deviation, band(half_width), {});
      const DefectResult shared = findDefects(surface, scan.deviation, band(half_width), {});
      ASSERT_GE(alone.regions.size(), 2u);
      expectSameRegions(shared, alone);
      EXPECT_EQ(shared.point_region, alone.point_region);
    }
  }
}

TEST(Defects, SmallRegionsAndUnmatchedPointsAreNotDefects) {
  // A 1 mm-radius bump covers ~12 grid points: reported with min_points 5, not with 20.
  const SurfaceDefect bump{Eigen::Vector3d(0.0, 0.0, 0.0), 0.001, 5e-4};
  PlaneScan scan = scanPlane({bump}, 0.0, 1);
  DefectConfig config;
  config.min_points = 5;
  EXPECT_EQ(findDefects(scan.points, scan.faces, scan.deviation, band(1e-4), config).regions.size(),
            1u);
  config.min_points = 20;
  EXPECT_TRUE(
      findDefects(scan.points, scan.faces, scan.deviation, band(1e-4), config).regions.empty());
  // The same points unmatched (no CAD near them): nothing to judge.
  for (auto& d : scan.deviation) {
    if (d > 1e-4F) {
      d = std::numeric_limits<float>::quiet_NaN();
    }
  }
  config.min_points = 5;
  EXPECT_TRUE(
      findDefects(scan.points, scan.faces, scan.deviation, band(1e-4), config).regions.empty());
}

// A region under defects.min_area is dropped whatever its point count, on a mesh and on a cloud,
// and its points belong to no region; a larger one stays, first in the list.
TEST(Defects, RegionsUnderTheMinimumAreaAreNotDefects) {
  const SurfaceDefect small{Eigen::Vector3d(-0.02, 0.0, 0.0), 0.002, -6e-4};
  const SurfaceDefect large{Eigen::Vector3d(0.02, 0.0, 0.0), 0.005, 4e-4};
  const double small_area = discAbove(small, 1e-4);
  const double large_area = discAbove(large, 1e-4);
  const PlaneScan scan = scanPlane({small, large}, 0.0, 1);
  for (const bool mesh : {true, false}) {
    SCOPED_TRACE(mesh ? "mesh" : "cloud");
    const Triangles faces = mesh ? scan.faces : Triangles();
    DefectConfig config;
    const DefectResult both = findDefects(scan.points, faces, scan.deviation, band(1e-4), config);
    ASSERT_EQ(both.regions.size(), 2u);
    EXPECT_EQ(both.regions[0].sign, -1);  // the deeper one first
    config.min_area = std::sqrt(small_area * large_area);
    std::printf("  areas %.3g and %.3g mm^2, min_area %.3g mm^2\n",
                small_area * 1e6,
                large_area * 1e6,
                config.min_area * 1e6);
    const DefectResult kept = findDefects(scan.points, faces, scan.deviation, band(1e-4), config);
    ASSERT_EQ(kept.regions.size(), 1u);
    EXPECT_EQ(kept.regions[0].sign, 1);
    EXPECT_NEAR(kept.regions[0].area, large_area, 0.1 * large_area);
    EXPECT_EQ(kept.regions[0].points, both.regions[1].points);
    for (std::size_t i = 0; i < scan.points.size(); ++i) {
      EXPECT_EQ(kept.point_region[i], both.point_region[i] == 1 ? 0 : -1);
    }
  }
}

// A bump across the border of a named region (regions.h): its points are judged against their
// own region's band, and points of two regions never join one defect.
TEST(Defects, ABumpAcrossARegionsBorderIsJudgedOnEachSideByThatSidesBand) {
  const SurfaceDefect bump{Eigen::Vector3d(0.0, 0.0, 0.0), 0.008, 6e-4};
  for (const bool mesh : {true, false}) {
    SCOPED_TRACE(mesh ? "mesh" : "cloud");
    const PlaneScan scan = scanPlane({bump}, 0.0, 1);
    const Triangles faces = mesh ? scan.faces : Triangles();
    RegionConfig left;
    left.name = "left";
    left.boxes.push_back({Eigen::Vector3d(-1.0, -1.0, -1.0), Eigen::Vector3d(0.0, 1.0, 1.0)});
    std::vector<RegionConfig> regions = {left};
    const std::vector<int> region_of = regionOf(regions, scan.points);
    const DefectResult whole = findDefects(scan.points, faces, scan.deviation, band(1e-4), {});
    ASSERT_EQ(whole.regions.size(), 1u);
    // The same band on both sides: the bump falls in two halves, one per side.
    const DefectResult split = findDefects(
        scan.points, faces, scan.deviation, toleranceBands(regions, region_of, band(1e-4)), {});
    ASSERT_EQ(split.regions.size(), 2u);
    EXPECT_NE(split.regions[0].region, split.regions[1].region);
    EXPECT_EQ(split.regions[0].points + split.regions[1].points, whole.regions[0].points);
    for (const DefectRegion& half : split.regions) {
      EXPECT_EQ(half.region<0, half.centroid.x()> 0.0);  // the rest of the part is x > 0
      EXPECT_NEAR(half.peak, 6e-4, 2e-5);  // the bump's top is on the border: both reach it
    }
    // A band on the left that the bump stays inside: only the right half is a defect.
    regions[0].has_tolerance = true;
    regions[0].tolerance = band(1e-3);
    const DefectResult right = findDefects(
        scan.points, faces, scan.deviation, toleranceBands(regions, region_of, band(1e-4)), {});
    ASSERT_EQ(right.regions.size(), 1u);
    EXPECT_EQ(right.regions[0].region, -1);
    EXPECT_GT(right.regions[0].centroid.x(), 0.0);
    for (std::size_t i = 0; i < scan.points.size(); ++i) {
      if (scan.points[i].x() < 0.0) {
        EXPECT_EQ(right.point_region[i], -1);
      }
    }
  }
}

TEST(Defects, ConfigurationIsChecked) {
  DefectConfig config;
  EXPECT_TRUE(validate(config).empty());
  config.min_points = 0;
  config.neighbour_spacings = 0.5;
  EXPECT_EQ(validate(config).size(), 2u);
  config = DefectConfig();
  for (const double area : {-1e-6, std::numeric_limits<double>::quiet_NaN()}) {
    config.min_area = area;
    ASSERT_EQ(validate(config).size(), 1u);
    EXPECT_NE(validate(config)[0].find("defects.min_area"), std::string::npos);
  }
}

}  // namespace
}  // namespace freeform_inspection
