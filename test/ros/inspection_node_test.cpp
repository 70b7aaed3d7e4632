// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// rostest client: the node starts with the shipped blade, publishes the CAD marker, answers
// Inspect with a status for every kind of request and keeps serving after bad ones. The nodelet
// test runs the same cases against the nodelet in a namespace.
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "analytic_clouds.h"
#include "rostest_helpers.h"
#include <gtest/gtest.h>
#include <ros/master.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/Marker.h>

#include "freeform_inspection/io.h"
#include "freeform_inspection/surface_defect.h"
#include <freeform_inspection/Inspect.h>
#include <freeform_inspection/InspectionReport.h>
#include <freeform_inspection/LoadModel.h>

namespace {

using freeform_inspection::Inspect;
using freeform_inspection::InspectionReport;
using freeform_inspection::LoadModel;
using namespace freeform_inspection_rostest;  // NOLINT(google-build-using-namespace): test helpers

TEST(InspectionNode, PublishesLatchedCadMarkerInMetresInPartFrame) {
  const auto marker =
      ros::topic::waitForMessage<visualization_msgs::Marker>(nodeName() + "/model_marker", kWait);
  ASSERT_TRUE(marker) << "no latched marker on " << nodeName() << "/model_marker";
  EXPECT_EQ(marker->header.frame_id, "part");
  EXPECT_EQ(marker->type, visualization_msgs::Marker::TRIANGLE_LIST);
  const auto model = freeform_inspection::loadMesh(param("model_path"), 0.001);
  ASSERT_TRUE(model.status.ok()) << model.status.message;
  EXPECT_EQ(marker->points.size(), 3 * model.mesh.faces.size());
  double max_abs = 0.0;
  for (const auto& p : marker->points) {
    max_abs = std::max({max_abs, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  }
  EXPECT_GT(max_abs, 0.05) << "the blade is ~0.1 m: marker not in metres?";
  EXPECT_LT(max_abs, 0.5) << "the blade is ~0.1 m: mm not converted to metres?";
}

// Latest message on `topic` published after `call` ran (subscribed before it).
template <typename Message, typename Call>
boost::shared_ptr<const Message> receiveDuring(const std::string& topic, Call call) {
  ros::NodeHandle nh;
  boost::shared_ptr<const Message> received;
  std::mutex mutex;
  ros::Subscriber sub =
      nh.subscribe<Message>(topic, 1, [&](const boost::shared_ptr<const Message>& message) {
        std::lock_guard<std::mutex> lock(mutex);
        received = message;
      });
  for (int i = 0; i < 100 && sub.getNumPublishers() == 0; ++i) {
    ros::Duration(0.05).sleep();  // connection handshake, not a result wait
  }
  call();
  for (int i = 0; i < 200; ++i) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (received) {
        return received;
      }
    }
    ros::Duration(0.05).sleep();
  }
  return nullptr;
}

TEST(InspectionNode, RegistersTheSampleScanJudgesItAndPublishesPoseAndDeviation) {
  const auto scan = freeform_inspection::loadScan(param("sample_scan"), 1.0);
  ASSERT_TRUE(scan.status.ok()) << scan.status.message;
  Inspect::Response response;
  const auto cloud = receiveDuring<sensor_msgs::PointCloud2>(nodeName() + "/deviation", [&] {
    response = callInspect(cloudRequest(toCloud(scan.scan.points, "scanner")));
  });
  // The sample is the CAD sampled with σ = 0.02 mm noise: inside the default ±0.1 mm band.
  EXPECT_EQ(response.status, Inspect::Response::PASS) << response.message;
  EXPECT_EQ(response.report.registration_status, "ok") << response.message;
  const auto& deviation = response.report.deviation;
  EXPECT_NEAR(deviation.std, 2e-5, 0.2 * 2e-5);
  EXPECT_NEAR(deviation.mean, 0.0, 5e-6);
  EXPECT_GT(deviation.in_tolerance_fraction, 0.999);
  EXPECT_GT(deviation.coverage, 0.95);
  EXPECT_EQ(deviation.n_points + deviation.n_unmatched, scan.scan.points.size());
  EXPECT_EQ(deviation.histogram_edges.size(), deviation.histogram_counts.size() + 1);
  EXPECT_TRUE(response.report.defects.empty());
  // The report carries the part's pose in the scan frame: inverse(T_cad_scan).
  expectSamplePose(tf2::transformToEigen(response.report.transform), "report.transform");
  EXPECT_EQ(response.report.part_id, "sn-0001");
  EXPECT_TRUE(std::isnan(response.report.offset_from_guess_deg)) << "searched, no guess";
  EXPECT_EQ(response.report.counts.scan_points, scan.scan.points.size());
  EXPECT_EQ(response.report.counts.scan_faces, 0u) << "an unorganized cloud has no faces";
  EXPECT_EQ(response.report.header.frame_id, "scanner");
  EXPECT_EQ(response.report.transform.child_frame_id, "part");
  // The same pose on tf, at the scan's stamp.
  const auto on_tf = partOnTf(ros::Time(1234.5));
  ASSERT_TRUE(on_tf) << "no scanner → part transform on tf at the scan's stamp";
  expectSamplePose(*on_tf, "tf scanner → part");
  // The deviation cloud: every scan point, in the part frame, with its named fields.
  ASSERT_TRUE(cloud) << "no cloud on ~deviation";
  EXPECT_EQ(cloud->header.frame_id, "part");
  EXPECT_EQ(cloud->header.stamp, ros::Time(1234.5));
  EXPECT_EQ(static_cast<std::size_t>(cloud->width) * cloud->height, scan.scan.points.size());
  std::vector<std::string> fields;
  for (const auto& field : cloud->fields) {
    fields.push_back(field.name);
  }
  EXPECT_EQ(
      fields,
      (std::vector<std::string>{"x", "y", "z", "deviation", "in_tolerance", "region", "rgb"}));
  sensor_msgs::PointCloud2ConstIterator<float> x(*cloud, "x");
  sensor_msgs::PointCloud2ConstIterator<float> d(*cloud, "deviation");
  sensor_msgs::PointCloud2ConstIterator<std::int32_t> r(*cloud, "region");
  const Eigen::Isometry3d T_cad_scan = sampleTruth();
  double worst = 0.0;
  for (std::size_t i = 0; i < scan.scan.points.size(); i += 97, x += 97, d += 97, r += 97) {
    // In the part frame: the truth maps the scan point there, up to the pose error.
    const Eigen::Vector3d expected = T_cad_scan * scan.scan.points[i];
    worst = std::max(worst, (Eigen::Vector3d(x[0], x[1], x[2]) - expected).norm());
    EXPECT_LT(std::abs(*d), 1e-4);
    EXPECT_EQ(*r, -1) << "no named regions";
  }
  EXPECT_LT(worst, 0.0005);
  const auto result =
      ros::topic::waitForMessage<InspectionReport>(nodeName() + "/result", ros::Duration(5.0));
  ASSERT_TRUE(result) << "no latched report on ~result";
  EXPECT_EQ(result->part_id, "sn-0001");
}

TEST(InspectionNode, DentedScanFailsWithTheDentInPlaceAndTighterToleranceFails) {
  auto scan = freeform_inspection::loadScan(param("sample_scan"), 1.0);
  ASSERT_TRUE(scan.status.ok()) << scan.status.message;
  ASSERT_EQ(scan.scan.normals.size(), scan.scan.points.size());
  // A 0.5 mm deep, 8 mm wide dent on the face nearest the scan's centroid.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : scan.scan.points) {
    centroid += p / static_cast<double>(scan.scan.points.size());
  }
  std::size_t nearest = 0;
  for (std::size_t i = 0; i < scan.scan.points.size(); ++i) {
    if ((scan.scan.points[i] - centroid).norm() < (scan.scan.points[nearest] - centroid).norm()) {
      nearest = i;
    }
  }
  const freeform_inspection::SurfaceDefect dent{scan.scan.points[nearest], 0.008, -0.0005};
  const Eigen::Vector3d facing = scan.scan.normals[nearest];
  freeform_inspection::Scan dented = scan.scan;
  for (std::size_t i = 0; i < dented.points.size(); ++i) {
    if (dented.normals[i].dot(facing) > 0.5) {
      dented.points[i] +=
          freeform_inspection::defectDisplacement(dent, scan.scan.points[i]) * dented.normals[i];
    }
  }
  const auto response = callInspect(cloudRequest(toCloud(dented.points, "scanner")));
  EXPECT_EQ(response.status, Inspect::Response::FAIL) << response.message;
  ASSERT_FALSE(response.report.defects.empty()) << response.message;
  const auto& found = response.report.defects.front();
  const Eigen::Vector3d where = sampleTruth() * dent.centre;
  const Eigen::Vector3d centre(found.centroid.x, found.centroid.y, found.centroid.z);
  EXPECT_EQ(response.report.defects.size(), 1u);
  EXPECT_EQ(found.sign, -1);
  EXPECT_LT((centre - where).norm(), dent.radius);
  EXPECT_NEAR(found.peak, dent.depth, 0.2 * std::abs(dent.depth));
  EXPECT_NE(response.message.find("dent"), std::string::npos) << response.message;

  // The clean scan against a ±0.01 mm band (half the noise σ): FAIL, the band came from the call.
  Inspect::Request tight = cloudRequest(toCloud(scan.scan.points, "scanner"));
  tight.tolerance_upper = 1e-5;
  tight.tolerance_lower = -1e-5;
  const auto strict = callInspect(tight);
  EXPECT_EQ(strict.status, Inspect::Response::FAIL) << strict.message;
  EXPECT_DOUBLE_EQ(strict.report.tolerance_upper, 1e-5);
  EXPECT_LT(strict.report.deviation.in_tolerance_fraction, 0.5);
}

// A known pose (the fixture's nominal) in the scan's frame: refined by ICP, no features sought;
// a guess tf cannot place, a broken quaternion and another child frame are refused by name.
TEST(InspectionNode, InitialGuessIsRefinedWithoutASearch) {
  const Eigen::Isometry3d truth = sampleTruth();  // T_cad_scan
  Eigen::Isometry3d off = Eigen::Isometry3d::Identity();
  off.linear() =
      Eigen::AngleAxisd(3.0 * M_PI / 180.0, Eigen::Vector3d(0.8, 0.0, 0.6)).toRotationMatrix();
  off.translation() = Eigen::Vector3d(0.0, 0.002, 0.0);
  Inspect::Request request = cloudRequest(sampleCloud());
  request.initial_guess = tf2::eigenToTransform(off * truth.inverse());  // part in the scan frame
  request.initial_guess.header.frame_id = "scanner";
  request.initial_guess.child_frame_id = "part";
  const Inspect::Response refined = callInspect(request);
  EXPECT_EQ(refined.status, Inspect::Response::PASS) << refined.message;
  EXPECT_EQ(refined.report.registration_status, "ok") << refined.message;
  EXPECT_EQ(refined.report.counts.features, 0u);
  EXPECT_NEAR(refined.report.offset_from_guess_deg, 3.0, 0.1);
  EXPECT_GT(refined.report.offset_from_guess, 0.001);
  expectSamplePose(tf2::transformToEigen(refined.report.transform), "refined initial_guess");

  Inspect::Request elsewhere = request;
  elsewhere.initial_guess.header.frame_id = "no_such_frame";
  const auto lost = callInspect(elsewhere);
  EXPECT_EQ(lost.report.error_code, "TF_ERROR");
  EXPECT_NE(lost.message.find("no_such_frame"), std::string::npos) << lost.message;

  Inspect::Request broken = request;
  broken.initial_guess.transform.rotation = geometry_msgs::Quaternion();  // all zero
  const auto no_rotation = callInspect(broken);
  EXPECT_EQ(no_rotation.report.error_code, "INVALID_INPUT");
  EXPECT_TRUE(std::isnan(no_rotation.report.offset_from_guess_deg));
  EXPECT_NE(no_rotation.message.find("quaternion"), std::string::npos) << no_rotation.message;

  Inspect::Request other_child = request;
  other_child.initial_guess.child_frame_id = "fixture";
  const auto wrong_child = callInspect(other_child);
  EXPECT_EQ(wrong_child.report.error_code, "INVALID_INPUT");
  EXPECT_NE(wrong_child.message.find("'part'"), std::string::npos) << wrong_child.message;
}

// ALIGN_FIXED: the deviation at initial_guess as it is (a locating fixture). At the sample's true
// pose PASS; 1 mm off its seat FAIL, the pose still the guess, the offset 1 mm. ALIGN_ICP_ONLY
// and ALIGN_FIXED need a guess; an unknown alignment is refused.
TEST(InspectionNode, FixedAlignmentInspectsAtTheGuessAsItIs) {
  const Eigen::Isometry3d truth = sampleTruth();  // T_cad_scan
  Inspect::Request request = cloudRequest(sampleCloud());
  request.alignment = Inspect::Request::ALIGN_FIXED;
  request.initial_guess = tf2::eigenToTransform(truth.inverse());  // part in the scan frame
  request.initial_guess.header.frame_id = "scanner";
  const Inspect::Response at_truth = callInspect(request);
  EXPECT_EQ(at_truth.status, Inspect::Response::PASS) << at_truth.message;
  EXPECT_EQ(at_truth.report.registration_status, "fixed") << at_truth.message;
  EXPECT_LT(at_truth.report.offset_from_guess_deg, 0.1);
  EXPECT_LT(at_truth.report.offset_from_guess, 0.0001);
  expectSamplePose(tf2::transformToEigen(at_truth.report.transform), "fixed at the truth");

  Eigen::Isometry3d off_seat = Eigen::Isometry3d::Identity();
  off_seat.translation() = Eigen::Vector3d(0.001, 0.0, 0.0);  // 1 mm along the CAD's x
  Inspect::Request shifted = request;
  shifted.initial_guess = tf2::eigenToTransform((off_seat * truth).inverse());
  shifted.initial_guess.header.frame_id = "scanner";
  const Inspect::Response moved = callInspect(shifted);
  EXPECT_EQ(moved.status, Inspect::Response::FAIL) << moved.message;
  EXPECT_EQ(moved.report.registration_status, "fixed");
  EXPECT_NEAR(moved.report.offset_from_guess, 0.001, 0.0001);
  const Eigen::Isometry3d reported = tf2::transformToEigen(moved.report.transform);  // scan → part
  EXPECT_LT((reported.inverse().matrix() - (off_seat * truth).matrix()).cwiseAbs().maxCoeff(), 1e-9)
      << "the pose is the guess, not a fit";

  Inspect::Request no_guess = cloudRequest(sampleCloud());
  no_guess.alignment = Inspect::Request::ALIGN_FIXED;
  const auto fixed_without = callInspect(no_guess);
  EXPECT_EQ(fixed_without.report.error_code, "INVALID_INPUT");
  EXPECT_NE(fixed_without.message.find("ALIGN_FIXED needs initial_guess"), std::string::npos)
      << fixed_without.message;
  no_guess.alignment = Inspect::Request::ALIGN_ICP_ONLY;
  EXPECT_EQ(callInspect(no_guess).report.error_code, "INVALID_INPUT");
  no_guess.alignment = 7;
  const auto unknown = callInspect(no_guess);
  EXPECT_EQ(unknown.report.error_code, "INVALID_INPUT");
  EXPECT_NE(unknown.message.find("alignment 7"), std::string::npos) << unknown.message;
}

TEST(InspectionNode, RefusesBadRequestsWithReasonsAndKeepsServing) {
  const auto empty = callInspect(cloudRequest(toCloud({}, "scanner")));
  EXPECT_EQ(empty.status, Inspect::Response::ERROR);
  EXPECT_EQ(empty.report.error_code, "INVALID_INPUT");
  EXPECT_NE(empty.message.find("no finite points"), std::string::npos) << empty.message;

  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto all_nan = callInspect(cloudRequest(toCloud({{nan, nan, nan}, {nan, 0, 0}}, "s")));
  EXPECT_EQ(all_nan.report.error_code, "INVALID_INPUT");

  sensor_msgs::PointCloud2 broken = toCloud({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, "s");
  broken.data.resize(5);  // width·height·point_step no longer matches the data
  const auto inconsistent = callInspect(cloudRequest(broken));
  EXPECT_EQ(inconsistent.report.error_code, "INVALID_INPUT");
  EXPECT_NE(inconsistent.message.find("data holds 5 bytes"), std::string::npos)
      << inconsistent.message;

  Inspect::Request no_scan = cloudRequest(toCloud({}, "s"));
  no_scan.use_last_scan = true;  // nothing was published on `scan`
  EXPECT_EQ(callInspect(no_scan).report.error_code, "NO_SCAN");

  const auto scan = freeform_inspection::loadScan(param("sample_scan"), 1.0);
  ASSERT_TRUE(scan.status.ok());
  freeform_inspection::Points in_mm;
  for (const auto& p : scan.scan.points) {
    in_mm.push_back(1000.0 * p);  // a scan in mm against a CAD in m: refused naming units
  }
  const auto units = callInspect(cloudRequest(toCloud(in_mm, "s")));
  EXPECT_EQ(units.report.error_code, "UNITS_MISMATCH");
  EXPECT_NE(units.message.find("units"), std::string::npos) << units.message;

  const auto good = callInspect(cloudRequest(toCloud(scan.scan.points, "s")));
  EXPECT_EQ(good.report.registration_status, "ok") << "node stopped serving after bad input";
}

TEST(InspectionNode, CropBoxFromTheParameterServerDropsWhatLiesOutside) {
  // The .test file sets ~input/crop_box to ±1000 m as a list of integers: 500 points of clutter
  // at 1.5 km go before anything else, counted, and the sample scan still passes.
  freeform_inspection::Points points =
      freeform_inspection::loadScan(param("sample_scan"), 1.0).scan.points;
  for (int i = 0; i < 500; ++i) {
    points.emplace_back(1500.0 + 0.001 * i, 1500.0, 1500.0);
  }
  const auto response = callInspect(cloudRequest(toCloud(points, "scanner")));
  EXPECT_EQ(response.status, Inspect::Response::PASS) << response.message;
  EXPECT_EQ(response.report.counts.cropped, 500u);
  EXPECT_EQ(response.report.counts.scan_points, points.size() - 500);
  EXPECT_EQ(response.report.deviation.n_invalid, 0u);
}

TEST(InspectionNode, OrganizedCloudWithNanPixelsIsReadOnItsGrid) {
  // A range image (height > 1) with NaN where the rays miss: the node passes the grid on, the
  // pipeline triangulates it, removes the NaN pixels and counts them.
  namespace analytic = freeform_inspection::analytic;
  const analytic::Pinhole camera{96, 64, 300.0};
  const analytic::OrganizedCloud image =
      analytic::organizedSphere(camera, Eigen::Vector3d(0, 0, 0.3), 0.05);
  sensor_msgs::PointCloud2 cloud = toCloud(image.points, "camera_optical");
  cloud.height = static_cast<std::uint32_t>(image.height);
  cloud.width = static_cast<std::uint32_t>(image.width);
  cloud.row_step = cloud.width * cloud.point_step;
  cloud.is_dense = true;  // drivers lie: the node must not trust it
  std::uint32_t holes = 0;
  for (const auto& p : image.points) {
    holes += p.allFinite() ? 0 : 1;
  }
  ASSERT_GT(holes, 0u);
  const auto response = callInspect(cloudRequest(cloud));
  // A sphere against the blade: never registered, and said so.
  EXPECT_NE(response.report.registration_status, "ok") << response.message;
  EXPECT_EQ(response.report.deviation.n_invalid, holes);
  EXPECT_EQ(response.report.counts.scan_points, image.points.size() - holes);
  EXPECT_GT(response.report.counts.scan_faces, image.points.size() - holes)
      << "an organized cloud must be triangulated on its grid";
}

TEST(InspectionNode, LoadModelRefusesBadPathsAndUnitsAndKeepsTheModel) {
  ASSERT_TRUE(ros::service::waitForService(nodeName() + "/load_model", kWait));
  LoadModel missing;
  missing.request.path = "/nonexistent/part.stl";
  missing.request.units = "mm";
  ASSERT_TRUE(ros::service::call(nodeName() + "/load_model", missing));
  EXPECT_FALSE(missing.response.success);
  EXPECT_NE(missing.response.message.find("/nonexistent/part.stl"), std::string::npos)
      << missing.response.message;

  // Outside the model directories (here: the start-up model's), whatever the path says.
  LoadModel escape;
  escape.request.path = "package://freeform_inspection/data/blade/../../package.xml";
  escape.request.units = "mm";
  ASSERT_TRUE(ros::service::call(nodeName() + "/load_model", escape));
  EXPECT_FALSE(escape.response.success);
  EXPECT_NE(escape.response.message.find("outside the model directories"), std::string::npos)
      << escape.response.message;

  LoadModel bad_units;
  bad_units.request.path = param("model_path");
  bad_units.request.units = "furlong";
  ASSERT_TRUE(ros::service::call(nodeName() + "/load_model", bad_units));
  EXPECT_FALSE(bad_units.response.success);
  EXPECT_NE(bad_units.response.message.find("furlong"), std::string::npos);

  LoadModel good;
  good.request.path = "package://freeform_inspection/data/blade/blade_fine.stl";
  good.request.units = "mm";
  ASSERT_TRUE(ros::service::call(nodeName() + "/load_model", good));
  EXPECT_TRUE(good.response.success) << good.response.message;
  EXPECT_GT(good.response.diagonal, 0.05);
  EXPECT_LT(good.response.diagonal, 0.5);
}

// ~load_model with the part's named regions (data/blade/blade_regions.yaml): each region is
// reported with its own band and verdict; loading the model again without them drops them; a
// bad regions file is refused and the model kept.
TEST(InspectionNode, LoadModelWithRegionsJudgesEachRegion) {
  ASSERT_TRUE(ros::service::waitForService(nodeName() + "/load_model", kWait));
  LoadModel with_regions;
  with_regions.request.path = "package://freeform_inspection/data/blade/blade_fine.stl";
  with_regions.request.units = "mm";
  with_regions.request.regions_uri = "package://freeform_inspection/data/blade/blade_regions.yaml";
  with_regions.request.points_uri = "package://freeform_inspection/data/blade/blade_points.yaml";
  ASSERT_TRUE(ros::service::call(nodeName() + "/load_model", with_regions));
  ASSERT_TRUE(with_regions.response.success) << with_regions.response.message;
  // The part's band far below the sample's noise (σ 0.02 mm): the airfoil fails, the root holds
  // in its own ±0.5 mm band, the tip is left out.
  Inspect::Request request = cloudRequest(sampleCloud());
  request.tolerance_upper = 0.00001;
  request.tolerance_lower = -0.00001;
  Inspect::Response judged;
  const auto cloud = receiveDuring<sensor_msgs::PointCloud2>(
      nodeName() + "/deviation", [&] { judged = callInspect(request); });
  EXPECT_EQ(judged.status, Inspect::Response::FAIL) << judged.message;
  const InspectionReport& report = judged.report;
  ASSERT_EQ(report.regions.size(), 2u);
  EXPECT_EQ(report.regions[0].name, "tip");
  EXPECT_FALSE(report.regions[0].evaluated);
  EXPECT_EQ(report.regions[0].status, InspectionReport::NOT_EVALUATED);
  EXPECT_GT(report.regions[0].deviation.n_points, 0u);
  EXPECT_EQ(report.deviation.n_excluded, report.regions[0].deviation.n_points);
  EXPECT_EQ(report.regions[1].name, "root");
  EXPECT_EQ(report.regions[1].status, InspectionReport::PASS) << report.regions[1].message;
  EXPECT_EQ(report.regions[1].tolerance_upper, 0.0005);
  EXPECT_EQ(report.regions[1].defects, 0u);
  ASSERT_FALSE(report.defects.empty());
  for (const auto& defect : report.defects) {
    EXPECT_EQ(defect.region, "") << "the airfoil is the rest of the part";
  }
  // The deviation cloud names each point's region by its place in the report's list.
  ASSERT_TRUE(cloud) << "no cloud on ~deviation";
  std::size_t per_region[2] = {0, 0};
  sensor_msgs::PointCloud2ConstIterator<std::int32_t> region(*cloud, "region");
  for (; region != region.end(); ++region) {
    ASSERT_GE(*region, -1);
    ASSERT_LE(*region, 1);
    per_region[0] += *region == 0 ? 1 : 0;
    per_region[1] += *region == 1 ? 1 : 0;
  }
  EXPECT_EQ(per_region[0], report.regions[0].deviation.n_points);
  EXPECT_EQ(per_region[1], report.regions[1].deviation.n_points);
  // The model's comparison points, read where the sample is smooth: a few µm against σ 0.02 mm.
  ASSERT_EQ(report.comparison_points.size(), 3u);
  EXPECT_EQ(report.comparison_points[0].name, "span_25");
  EXPECT_EQ(report.comparison_points[0].tolerance_upper, 0.00001);  // the request's band
  const auto& span_50 = report.comparison_points[1];
  EXPECT_EQ(span_50.name, "span_50");
  EXPECT_EQ(span_50.tolerance_upper, 0.00005);  // its own
  EXPECT_EQ(span_50.status, InspectionReport::PASS) << span_50.message;
  for (const auto& point : report.comparison_points) {
    EXPECT_GE(point.points, 3u) << point.name;
    EXPECT_LT(std::abs(point.deviation), 3e-5) << point.name;
    EXPECT_NEAR(point.normal.x * point.normal.x + point.normal.y * point.normal.y +
                    point.normal.z * point.normal.z,
                1.0,
                1e-9);
  }
  EXPECT_EQ(report.comparison_points[2].name, "near_tip");
  EXPECT_EQ(report.comparison_points[2].datum, "");
  EXPECT_EQ(report.alignment, "best_fit");
  EXPECT_EQ(report.best_fit_transform, report.transform.transform);

  LoadModel bad = with_regions;
  bad.request.regions_uri = "package://freeform_inspection/data/blade/no_such_regions.yaml";
  ASSERT_TRUE(ros::service::call(nodeName() + "/load_model", bad));
  EXPECT_FALSE(bad.response.success);
  EXPECT_NE(bad.response.message.find("no_such_regions.yaml"), std::string::npos)
      << bad.response.message;
  EXPECT_EQ(callInspect(request).report.regions.size(), 2u) << "the model and its regions kept";
  LoadModel bad_points = with_regions;
  bad_points.request.points_uri = "package://freeform_inspection/data/blade/blade_regions.yaml";
  ASSERT_TRUE(ros::service::call(nodeName() + "/load_model", bad_points));
  EXPECT_FALSE(bad_points.response.success);
  EXPECT_NE(bad_points.response.message.find("a list under 'points:'"), std::string::npos)
      << bad_points.response.message;

  LoadModel without = with_regions;
  without.request.regions_uri = "";
  without.request.points_uri = "";
  ASSERT_TRUE(ros::service::call(nodeName() + "/load_model", without));
  ASSERT_TRUE(without.response.success) << without.response.message;
  const InspectionReport plain = callInspect(request).report;
  EXPECT_TRUE(plain.regions.empty());
  EXPECT_TRUE(plain.comparison_points.empty());

  // The six-point nest: the pose published is the frame its targets fix, a few hundredths of a
  // degree (the readings' noise) from the best fit, which the report keeps beside it.
  LoadModel with_datums = without;
  with_datums.request.points_uri = "package://freeform_inspection/data/blade/blade_datums.yaml";
  ASSERT_TRUE(ros::service::call(nodeName() + "/load_model", with_datums));
  ASSERT_TRUE(with_datums.response.success) << with_datums.response.message;
  Inspect::Request usual = cloudRequest(sampleCloud());
  usual.tolerance_upper = 0.0002;
  usual.tolerance_lower = -0.0002;
  const Inspect::Response datums = callInspect(usual);
  EXPECT_EQ(datums.status, Inspect::Response::PASS) << datums.message;
  EXPECT_EQ(datums.report.alignment, "datums") << datums.report.alignment_message;
  ASSERT_EQ(datums.report.comparison_points.size(), 6u);
  EXPECT_EQ(datums.report.comparison_points[5].datum, "C");
  for (const auto& target : datums.report.comparison_points) {
    EXPECT_LT(std::abs(target.deviation), 1e-6) << target.name;
  }
  const Eigen::Isometry3d found = tf2::transformToEigen(datums.report.transform.transform);
  const Eigen::Isometry3d best = tf2::transformToEigen(datums.report.best_fit_transform);
  const double apart = Eigen::AngleAxisd(found.linear().transpose() * best.linear()).angle();
  EXPECT_GT(apart, 0.0);
  EXPECT_LT(apart * 180.0 / M_PI, 0.2);
  ASSERT_TRUE(ros::service::call(nodeName() + "/load_model", without));
}

// Provider node of `service` according to the master, "" if none.
std::string serviceProvider(const std::string& service) {
  XmlRpc::XmlRpcValue args;
  XmlRpc::XmlRpcValue result;
  XmlRpc::XmlRpcValue payload;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", args, result, payload, true)) {
    return "";
  }
  XmlRpc::XmlRpcValue& services = payload[2];  // [publishers, subscribers, services]
  for (int i = 0; i < services.size(); ++i) {
    if (static_cast<std::string>(services[i][0]) == service && services[i][1].size() > 0) {
      return static_cast<std::string>(services[i][1][0]);
    }
  }
  return "";
}

// Only in the nodelet test: the master names the manager as the services' provider, so the class
// really runs inside the manager (where clouds from other nodelets arrive uncopied).
TEST(InspectionNodelet, ServesFromInsideTheManager) {
  ASSERT_TRUE(ros::service::waitForService(nodeName() + "/inspect", kWait));
  EXPECT_EQ(serviceProvider(nodeName() + "/inspect"), param("manager"));
}

}  // namespace
