// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// The CLI contract of design.md §5: JSON on stdout, exit 0 when it ran, exit 2 with one line on
// stderr for bad input or usage.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "report_test_util.h"
#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "freeform_inspection/io.h"

#ifndef FREEFORM_CLI_PATH
#error "FREEFORM_CLI_PATH must name the freeform_inspect executable"
#endif
#ifndef FREEFORM_DATA_DIR
#error "FREEFORM_DATA_DIR must name the package's data directory"
#endif
#ifndef FREEFORM_CORE_PATH
#error "FREEFORM_CORE_PATH must name the core library's file"
#endif

namespace {

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// This process's own scratch directory under the test temp dir, removed when the tests end:
// two runs side by side (a hand run beside CI) never share or delete each other's files.
const std::filesystem::path& scratch() {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path made =
        std::filesystem::path(::testing::TempDir()) / ("cli_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(made);
    return made;
  }();
  return dir;
}

class ScratchCleanup : public ::testing::Environment {
 public:
  void TearDown() override {
    std::error_code ignored;
    std::filesystem::remove_all(scratch(), ignored);
  }
};
const auto* const kScratchCleanup = ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

std::string temp(const std::string& name) {
  return (scratch() / name).string();
}

std::string slurp(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// The model cache of a run that names none: the test's own, never the user's ~/.cache.
const std::string kDefaultCache = temp("xdg_cache");

CliRun runCli(const std::string& args) {
  const std::string err_path = temp("stderr.txt");
  const std::string command = "XDG_CACHE_HOME=" + kDefaultCache + " " +
                              std::string(FREEFORM_CLI_PATH) + " " + args + " 2>" + err_path;
  CliRun run;
  FILE* pipe = popen(command.c_str(), "r");
  char buffer[4096];
  std::size_t n = 0;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) {
    run.out.append(buffer, n);
  }
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.err = slurp(err_path);
  return run;
}

const std::string kBlade = std::string(FREEFORM_DATA_DIR) + "/blade/blade.stl";
const std::string kBladeFine = std::string(FREEFORM_DATA_DIR) + "/blade/blade_fine.stl";
const std::string kScan = std::string(FREEFORM_DATA_DIR) + "/blade/blade_scan.ply";
const std::string kTruth = std::string(FREEFORM_DATA_DIR) + "/blade/blade_scan_T_cad_scan.txt";

int lineCount(const std::string& text) {
  int lines = 0;
  for (char c : text) {
    lines += c == '\n' ? 1 : 0;
  }
  return lines;
}

// The sample scan's true scan → CAD transform, written beside it by generate_blade.
Eigen::Matrix4d sampleTruth() {
  std::ifstream file(kTruth);
  Eigen::Matrix4d truth;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      file >> truth(r, c);
    }
  }
  EXPECT_TRUE(file) << kTruth;
  return truth;
}

Eigen::Matrix4d reportedPose(const nlohmann::json& json) {
  Eigen::Matrix4d pose;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      pose(r, c) = json["transform_cad_from_scan"][r][c].get<double>();
    }
  }
  return pose;
}

double turnDeg(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) {
  const Eigen::Matrix3d relative = a.topLeftCorner<3, 3>().transpose() * b.topLeftCorner<3, 3>();
  return Eigen::AngleAxisd(relative).angle() * 180.0 / M_PI;
}

// The first three rows of a transform, row-major, as --initial-pose takes them.
std::string poseArgument(const Eigen::Matrix4d& pose) {
  std::ostringstream text;
  text.precision(17);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      text << (r + c > 0 ? " " : "") << pose(r, c);
    }
  }
  return "\"" + text.str() + "\"";
}

TEST(Cli, HelpExitsZeroAndShowsTheContract) {
  const CliRun run = runCli("--help");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("--cad-scale"), std::string::npos);
}

TEST(Cli, UsageErrorsExitTwoWithOneLineOnStderr) {
  for (const std::string args :
       {"",
        "--cad",
        "--cad a.stl",
        "--cad a.stl --scan b.ply --bogus 1",
        "--cad a.stl --scan b.ply --cad-scale -1",
        "--cad a.stl --scan b.ply --tolerance abc",
        "--cad a.stl --scan b.ply --initial-pose '1 0 0 0 0 1 0 0'",
        "--cad a.stl --scan b.ply --initial-pose '1 0 0 0 0 1 0 0 0 0 1 x'",
        "--cad a.stl --scan b.ply --initial-pose "
        "'1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1'"}) {
    const CliRun run = runCli(args);
    EXPECT_EQ(run.exit_code, 2) << args;
    EXPECT_EQ(lineCount(run.err), 1) << args << ": " << run.err;
    EXPECT_TRUE(run.out.empty()) << args;
  }
}

// A known pose (a fixture's nominal) is refined by ICP without the search: the truth turned by
// 3° and moved 2 mm comes back within 0.1° of it; one that is no rigid transform is bad input.
TEST(Cli, InitialPoseIsRefinedWithoutTheSearch) {
  const Eigen::Matrix4d truth = sampleTruth();
  Eigen::Matrix4d off = Eigen::Matrix4d::Identity();
  off.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(3.0 * M_PI / 180.0, Eigen::Vector3d(0.0, 0.6, 0.8)).toRotationMatrix();
  off.topRightCorner<3, 1>() = Eigen::Vector3d(0.002, 0.0, 0.0);
  const std::string args = "--cad " + kBladeFine + " --cad-scale 0.001 --scan " + kScan +
                           " --tolerance 0.0002 --initial-pose ";
  const CliRun run = runCli(args + poseArgument(off * truth));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["status"], "ok") << json["message"];
  EXPECT_EQ(json["verdict"], "PASS") << json["verdict_reason"];
  const Eigen::Matrix4d pose = reportedPose(json);
  EXPECT_LT(turnDeg(pose, truth), 0.1);
  EXPECT_LT((pose.topRightCorner<3, 1>() - truth.topRightCorner<3, 1>()).norm(), 0.0005);
  EXPECT_EQ(json["counts"]["features"].get<int>(), 0);
  EXPECT_FALSE(json["timings_s"].contains("global_registration"));
  EXPECT_NEAR(json["offset_from_initial"]["rotation_deg"].get<double>(), 3.0, 0.1);
  EXPECT_GT(json["offset_from_initial"]["translation"].get<double>(), 0.001);
  // The report's own transform pasted back as it is (nested lists, 16 numbers).
  const CliRun again = runCli(args + "'" + json["transform_cad_from_scan"].dump() + "'");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_LT(turnDeg(reportedPose(nlohmann::json::parse(again.out)), pose), 0.01);
  Eigen::Matrix4d stretched = truth;
  stretched.topLeftCorner<3, 3>() *= 2.0;
  const CliRun refused = runCli(args + poseArgument(stretched));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(lineCount(refused.err), 1) << refused.err;
  EXPECT_NE(refused.err.find("rigid"), std::string::npos) << refused.err;
}

// --fixed-pose: the deviation at the given pose, not registered (a locating fixture). The pose is
// reported as given; how far the part sits from it is measured apart (offset_from_initial).
TEST(Cli, FixedPoseIsInspectedAsItIs) {
  const Eigen::Matrix4d truth = sampleTruth();
  const std::string args = "--cad " + kBladeFine + " --cad-scale 0.001 --scan " + kScan +
                           " --tolerance 0.0002 --fixed-pose ";
  const CliRun at_truth = runCli(args + poseArgument(truth));
  ASSERT_EQ(at_truth.exit_code, 0) << at_truth.err;
  const nlohmann::json json = nlohmann::json::parse(at_truth.out);
  EXPECT_EQ(json["status"], "fixed") << json["message"];
  EXPECT_EQ(json["verdict"], "PASS") << json["verdict_reason"];
  EXPECT_LT((reportedPose(json) - truth).cwiseAbs().maxCoeff(), 1e-12) << "the pose as given";
  EXPECT_LT(json["offset_from_initial"]["rotation_deg"].get<double>(), 0.1);
  EXPECT_LT(json["offset_from_initial"]["translation"].get<double>(), 0.0001);
  EXPECT_TRUE(json["pose_uncertainty"].is_null()) << "no fit, no covariance";
  EXPECT_FALSE(json["timings_s"].contains("global_registration"));
  EXPECT_LT(json["rmse"].get<double>(), 0.0001);
  // The part 1 mm off its seat along the CAD's x: FAIL at the given pose, which stays as given,
  // and the offset says how far it sits.
  Eigen::Matrix4d shifted = truth;
  shifted(0, 3) += 0.001;
  const CliRun off_seat = runCli(args + poseArgument(shifted));
  ASSERT_EQ(off_seat.exit_code, 0) << off_seat.err;
  const nlohmann::json off_json = nlohmann::json::parse(off_seat.out);
  EXPECT_EQ(off_json["status"], "fixed");
  EXPECT_EQ(off_json["verdict"], "FAIL") << off_json["verdict_reason"];
  EXPECT_LT((reportedPose(off_json) - shifted).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(off_json["offset_from_initial"]["translation"].get<double>(), 0.001, 0.0001);
  EXPECT_NE(off_json["warnings"].dump().find("sits"), std::string::npos) << off_json["warnings"];
  // The residual there is mostly the offset: the band is weighed against the scan's own noise.
  EXPECT_EQ(off_json["warnings"].dump().find("narrower than 3x"), std::string::npos)
      << off_json["warnings"];
  // Half a metre off: nothing of the scan on the CAD there, not evaluated, the offset unknown.
  shifted(0, 3) += 0.5;
  const CliRun away = runCli(args + poseArgument(shifted));
  ASSERT_EQ(away.exit_code, 0) << away.err;
  const nlohmann::json away_json = nlohmann::json::parse(away.out);
  EXPECT_EQ(away_json["verdict"], "NOT_EVALUATED") << away_json["verdict_reason"];
  EXPECT_TRUE(away_json["offset_from_initial"]["translation"].is_null());
  EXPECT_TRUE(away_json["rmse"].is_null());
  // Refining and fixing the pose at once is a usage error.
  const CliRun both = runCli(args + poseArgument(truth) + " --initial-pose " + poseArgument(truth));
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_EQ(lineCount(both.err), 1) << both.err;
  EXPECT_NE(both.err.find("exclude"), std::string::npos) << both.err;
  Eigen::Matrix4d mirrored = truth;
  mirrored.col(0) *= -1.0;
  const CliRun refused = runCli(args + poseArgument(mirrored));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("fixed pose is not a rigid"), std::string::npos) << refused.err;
}

TEST(Cli, MissingCadExitsTwoNamingTheFile) {
  const CliRun run = runCli("--cad /nonexistent/cad.stl --scan " + kScan);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(lineCount(run.err), 1);
  EXPECT_NE(run.err.find("/nonexistent/cad.stl"), std::string::npos) << run.err;
}

TEST(Cli, SampleRunPrintsTheJsonContractAndWritesTheReport) {
  const std::string report = temp("report.json");
  // The fine tessellation: the sample was sampled from it (σ = 0.02 mm), so the part is good.
  const CliRun run = runCli("--cad " + kBladeFine + " --cad-scale 0.001 --scan " + kScan +
                            " --tolerance 0.0002 --report " + report);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  for (const char* key : {"status",
                          "message",
                          "transform_cad_from_scan",
                          "rmse",
                          "fitness",
                          "verdict",
                          "deviation",
                          "defects",
                          "counts",
                          "timings_s"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json["status"], "ok") << json["message"];
  EXPECT_EQ(json["error_code"], "ok");
  EXPECT_EQ(json["verdict"], "PASS") << json["verdict_reason"];
  // The pose against the truth written next to the sample scan (generate_blade).
  const Eigen::Matrix4d truth = sampleTruth();
  const Eigen::Matrix4d pose = reportedPose(json);
  EXPECT_LT(turnDeg(pose, truth), 0.1);
  EXPECT_LT((pose.topRightCorner<3, 1>() - truth.topRightCorner<3, 1>()).norm(), 0.0005);
  EXPECT_LT(json["rmse"].get<double>(), 0.0001);
  EXPECT_GT(json["fitness"].get<double>(), 0.9);
  EXPECT_TRUE(json["offset_from_initial"]["rotation_deg"].is_null()) << "searched, no guess";
  EXPECT_GE(json["counts"]["features"].get<int>(), 3);
  EXPECT_GE(json["counts"]["correspondences"].get<int>(), 3);
  EXPECT_GT(json["counts"]["scan_points"].get<int>(), 10000);
  EXPECT_GT(json["counts"]["cad_vertices"].get<int>(), 5000);
  EXPECT_EQ(json["transform_cad_from_scan"].size(), 4u);
  EXPECT_TRUE(json["timings_s"].contains("total"));
  EXPECT_NEAR(json["deviation"]["rms"].get<double>(), 2e-5, 0.2 * 2e-5);
  EXPECT_NEAR(json["deviation"]["mean"].get<double>(), 0.0, 5e-6);
  EXPECT_GT(json["deviation"]["coverage"].get<double>(), 0.95);
  EXPECT_TRUE(json["defects"].empty());
  EXPECT_EQ(nlohmann::json::parse(slurp(report)), json) << "--report must hold the same JSON";
}

TEST(Cli, CoarseCadShowsItsChordalErrorAsExcessMaterial) {
  // The sample was sampled from the fine tessellation; the coarse STL's flat facets cut inside
  // the curved leading edge by up to ~0.6 mm, so the scan stands out of it there: FAIL, bumps.
  const CliRun run =
      runCli("--cad " + kBlade + " --cad-scale 0.001 --scan " + kScan + " --tolerance 0.0002");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["status"], "ok") << json["message"];
  EXPECT_EQ(json["verdict"], "FAIL") << json["verdict_reason"];
  ASSERT_FALSE(json["defects"].empty());
  const auto& largest = json["defects"][0];
  EXPECT_EQ(largest["sign"].get<int>(), 1);
  EXPECT_GT(largest["peak"].get<double>(), 0.0003);
  EXPECT_LT(largest["peak"].get<double>(), 0.001);
  EXPECT_NE(json["verdict_reason"].get<std::string>().find("bump"), std::string::npos);
}

std::string slurpBinary(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream bytes;
  bytes << file.rdbuf();
  return bytes.str();
}

// --deviation and --html on the registered sample: both files parse, and they agree with the JSON.
TEST(Cli, SampleRunWritesTheDeviationPlyAndTheHtmlReport) {
  namespace rt = freeform_inspection::report_test;
  const std::string ply = temp("deviation.ply");
  const std::string html_path = temp("report.html");
  std::remove(ply.c_str());
  std::remove(html_path.c_str());
  const std::string csv = temp("csv");
  const CliRun run = runCli("--cad " + kBlade + " --cad-scale 0.001 --scan " + kScan +
                            " --tolerance 0.0002 --deviation " + ply + " --html " + html_path +
                            " --csv " + csv + " --part-id 'SN 42, left'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  ASSERT_EQ(json["status"], "ok") << json["message"];
  EXPECT_TRUE(json.contains("verdict_reason"));
  EXPECT_EQ(json["part_id"], "SN 42, left");
  const auto& deviation = json["deviation"];
  EXPECT_EQ(deviation["histogram"]["edges"].size(), deviation["histogram"]["counts"].size() + 1);

  const freeform_inspection::ScanLoadResult cloud = freeform_inspection::loadScan(ply, 1.0);
  ASSERT_TRUE(cloud.status.ok()) << cloud.status.message;
  EXPECT_EQ(cloud.scan.points.size(), json["counts"]["scan_points"].get<std::size_t>());
  const std::vector<rt::DeviationVertex> vertices = rt::readDeviationVertices(slurpBinary(ply));
  ASSERT_EQ(vertices.size(), cloud.scan.points.size()) << "documented vertex layout";
  std::size_t in_tolerance = 0;
  std::size_t evaluated = 0;
  for (const rt::DeviationVertex& v : vertices) {
    in_tolerance += static_cast<std::size_t>(v.in_tolerance);
    evaluated += std::isnan(v.deviation) ? 0 : 1;
  }
  EXPECT_EQ(evaluated, deviation["evaluated"].get<std::size_t>());
  EXPECT_NEAR(static_cast<double>(in_tolerance) / static_cast<double>(evaluated),
              deviation["in_tolerance_fraction"].get<double>(),
              1e-3);

  const std::string html = slurp(html_path);
  EXPECT_NE(html.find(">" + json["verdict"].get<std::string>() + "<"), std::string::npos);
  EXPECT_NE(html.find(kScan), std::string::npos);
  EXPECT_NE(html.find("<td>SN 42, left</td>"), std::string::npos);
  EXPECT_NE(html.find("<svg class=\"histogram\""), std::string::npos);
  const std::vector<std::string> pngs = rt::dataUris(html, "image/png");
  ASSERT_EQ(pngs.size(), 3u);
  for (const std::string& bytes : pngs) {
    const rt::PngInfo png = rt::readPng(bytes);
    EXPECT_TRUE(png.error.empty()) << png.error;
    EXPECT_GT(png.width, 100);
    EXPECT_GT(png.height, 100);
  }

  // The CSV tables: the summary's numbers are the JSON's in millimetres, one histogram row per
  // bin, one defect row per defect (a header alone when there are none).
  const auto summary = rt::csvRows(slurp(csv + "/summary.csv"));
  ASSERT_EQ(summary.size(), 1u);
  const auto column = [&](const std::string& name) { return summary[0].at(name); };
  EXPECT_EQ(column("verdict"), json["verdict"]);
  EXPECT_EQ(column("scan_file"), kScan);
  EXPECT_EQ(column("part_id"), "SN 42, left");
  EXPECT_EQ(column("points_evaluated"), std::to_string(deviation["evaluated"].get<std::size_t>()));
  EXPECT_NEAR(std::stod(column("p95_mm")), 1e3 * deviation["p95"].get<double>(), 1e-4);
  EXPECT_NEAR(std::stod(column("upper_mm")), 0.2, 1e-9);
  const std::string histogram = slurp(csv + "/histogram.csv");
  EXPECT_EQ(static_cast<std::size_t>(std::count(histogram.begin(), histogram.end(), '\n')),
            deviation["histogram"]["counts"].size() + 1);
  const std::string defects = slurp(csv + "/defects.csv");
  EXPECT_EQ(static_cast<std::size_t>(std::count(defects.begin(), defects.end(), '\n')),
            json["defects"].size() + 1);
}

TEST(Cli, UnwritableOutputFileExitsTwoNamingIt) {
  // --csv makes its directory, so it is given one under a plain file, where none can be made.
  const std::string plain = temp("plain_file");
  std::ofstream(plain) << "x";
  for (const auto& [flag, path] : std::vector<std::pair<std::string, std::string>>{
           {"--html", "/nonexistent_dir_ffi/out.file"},
           {"--deviation", "/nonexistent_dir_ffi/out.file"},
           {"--csv", plain + "/csv"}}) {
    const CliRun run =
        runCli("--cad " + kBlade + " --cad-scale 0.001 --scan " + kScan + " " + flag + " " + path);
    EXPECT_EQ(run.exit_code, 2) << flag;
    EXPECT_EQ(lineCount(run.err), 1) << flag << ": " << run.err;
    EXPECT_NE(run.err.find(path), std::string::npos) << run.err;
  }
}

TEST(Cli, ScanInWrongUnitsExitsTwoNamingUnitsAndStillPrintsTheJson) {
  const CliRun run =
      runCli("--cad " + kBlade + " --cad-scale 0.001 --scan " + kScan + " --scan-scale 1000");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(lineCount(run.err), 1);
  EXPECT_NE(run.err.find("units"), std::string::npos) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["error_code"], "units_mismatch");
}

// Without a registration there is no deviation map: no PLY, a warning saying so, and an HTML
// report that records why the part was not evaluated.
TEST(Cli, UnregisteredScanSkipsTheDeviationFileButWritesTheReport) {
  const std::string ply = temp("unregistered.ply");
  const std::string html_path = temp("unregistered.html");
  std::remove(ply.c_str());
  std::remove(html_path.c_str());
  const CliRun run = runCli("--cad " + kBlade + " --cad-scale 0.001 --scan " + kScan +
                            " --scan-scale 1000 --deviation " + ply + " --html " + html_path);
  EXPECT_EQ(run.exit_code, 2);
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_FALSE(std::filesystem::exists(ply));
  bool warned = false;
  for (const auto& warning : json["warnings"]) {
    warned |= warning.get<std::string>().find("'" + ply + "' not written") != std::string::npos;
  }
  EXPECT_TRUE(warned) << json["warnings"];
  const std::string html = slurp(html_path);
  EXPECT_NE(html.find(">NOT_EVALUATED<"), std::string::npos);
  EXPECT_NE(html.find("No deviation map"), std::string::npos);
}

// verdict/measurement_uncertainty from --config: the report carries the zones of ISO 14253-1's
// rule (the band ±0.2 mm narrowed and widened by U = 0.05 mm). The coarse CAD's chordal error
// stands the sample scan up to ~0.6 mm out of it (CoarseCadShowsItsChordalErrorAsExcessMaterial),
// beyond the widened band too: nonconformance proven. A negative U is refused, naming the key.
TEST(Cli, GuardBandsFromTheConfigAreInTheReport) {
  const std::string config = temp("guard.yaml");
  std::ofstream(config) << "verdict:\n  measurement_uncertainty: 0.00005\n";
  const CliRun run = runCli("--cad " + kBlade + " --cad-scale 0.001 --scan " + kScan +
                            " --tolerance 0.0002 --config " + config);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  ASSERT_EQ(json["status"], "ok") << json["message"];
  const auto& zones = json["conformance"];
  ASSERT_TRUE(zones.is_object()) << zones;
  EXPECT_DOUBLE_EQ(zones["measurement_uncertainty"].get<double>(), 0.00005);
  EXPECT_NEAR(zones["acceptance_zone"][0].get<double>(), -0.00015, 1e-12);
  EXPECT_NEAR(zones["acceptance_zone"][1].get<double>(), 0.00015, 1e-12);
  EXPECT_NEAR(zones["rejection_limits"][1].get<double>(), 0.00025, 1e-12);
  EXPECT_GE(zones["regions_beyond_rejection"].get<int>(), 1);
  EXPECT_GE(zones["regions_outside_acceptance"].get<int>(),
            zones["regions_beyond_rejection"].get<int>());
  EXPECT_EQ(json["verdict"], "FAIL") << json["verdict_reason"];
  EXPECT_NE(json["verdict_reason"].get<std::string>().find("nonconformance proven"),
            std::string::npos);

  const CliRun plain = runCli("--cad " + kBlade + " --cad-scale 0.001 --scan " + kScan);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_TRUE(nlohmann::json::parse(plain.out)["conformance"].is_null());

  std::ofstream(config) << "verdict:\n  measurement_uncertainty: -0.00005\n";
  const CliRun refused = runCli("--cad " + kBlade + " --scan " + kScan + " --config " + config);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("measurement_uncertainty"), std::string::npos) << refused.err;
}

TEST(Cli, InvalidConfigExitsTwoNamingTheKey) {
  const std::string config = temp("bad.yaml");
  std::ofstream(config) << "tolerance:\n  uper: 0.001\n";
  const CliRun run = runCli("--cad " + kBlade + " --scan " + kScan + " --config " + config);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("tolerance/uper"), std::string::npos) << run.err;
}

// Named regions from --regions: each one reported with its band, statistics and verdict, the
// defects named by region; a region left out hides what lies in it; a bad file exits 2.
TEST(Cli, RegionsFileJudgesEachRegionWithItsOwnBand) {
  // The blade's root (the CAD's z below 20 mm) held to ±0.01 mm, its tip (z above 120 mm) left
  // out, the rest at ±0.2 mm; the sample's noise σ is 0.02 mm.
  const std::string regions = temp("regions.yaml");
  std::ofstream(regions) << "regions:\n"
                            "  - name: tip\n"
                            "    boxes: [{min: [-1, -1, 0.12], max: [1, 1, 1]}]\n"
                            "    evaluate: false\n"
                            "  - name: root\n"
                            "    boxes: [{min: [-1, -1, -1], max: [1, 1, 0.02]}]\n"
                            "    tolerance: {upper: 0.00001, lower: -0.00001}\n";
  const std::string args = "--cad " + kBladeFine + " --cad-scale 0.001 --scan " + kScan +
                           " --tolerance 0.0002 --initial-pose " + poseArgument(sampleTruth());
  const CliRun plain = runCli(args);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const nlohmann::json part = nlohmann::json::parse(plain.out);
  EXPECT_EQ(part["verdict"], "PASS") << part["verdict_reason"];
  EXPECT_TRUE(part["regions"].empty());
  const std::string ply = temp("regions_deviation.ply");
  const CliRun run = runCli(args + " --regions " + regions + " --deviation " + ply);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["verdict"], "FAIL") << json["verdict_reason"];
  ASSERT_EQ(json["regions"].size(), 2u);
  const nlohmann::json& tip = json["regions"][0];
  const nlohmann::json& root = json["regions"][1];
  EXPECT_EQ(tip["name"], "tip");
  EXPECT_EQ(tip["evaluated"], false);
  EXPECT_EQ(tip["verdict"], "NOT_EVALUATED");
  EXPECT_EQ(tip["tolerance"]["upper"], 0.0002);
  EXPECT_EQ(root["verdict"], "FAIL") << root["verdict_reason"];
  EXPECT_EQ(root["tolerance"]["lower"], -0.00001);
  EXPECT_LT(root["deviation"]["in_tolerance_fraction"].get<double>(), 0.6);
  // Every defect lies in the root, and the root counts them all.
  ASSERT_FALSE(json["defects"].empty());
  for (const auto& defect : json["defects"]) {
    EXPECT_EQ(defect["region"], "root");
  }
  EXPECT_EQ(root["defects"].get<std::size_t>(), json["defects"].size());
  // The part's points: the tip's are left out, and the rest are all accounted for.
  const std::size_t excluded = json["deviation"]["excluded"].get<std::size_t>();
  EXPECT_EQ(excluded, tip["deviation"]["evaluated"].get<std::size_t>());
  EXPECT_GT(excluded, 0u);
  EXPECT_EQ(json["deviation"]["evaluated"].get<std::size_t>() + excluded,
            part["deviation"]["evaluated"].get<std::size_t>());
  // The PLY names each measured point's region by its place in `regions`, and flags it in
  // tolerance by that region's band.
  namespace rt = freeform_inspection::report_test;
  const std::vector<rt::DeviationVertex> vertices = rt::readDeviationVertices(slurpBinary(ply));
  ASSERT_EQ(vertices.size(), json["counts"]["scan_points"].get<std::size_t>());
  std::size_t per_region[2] = {0, 0};
  for (const rt::DeviationVertex& v : vertices) {
    ASSERT_GE(v.region, -1);
    ASSERT_LE(v.region, 1);
    if (v.region < 0) {
      continue;
    }
    ASSERT_FALSE(std::isnan(v.deviation));
    ++per_region[v.region];
    if (v.region == 1) {
      EXPECT_EQ(v.in_tolerance, std::abs(v.deviation) <= 0.00001f ? 1 : 0) << v.deviation;
    }
  }
  EXPECT_EQ(per_region[0], tip["deviation"]["evaluated"].get<std::size_t>());
  EXPECT_EQ(per_region[1], root["deviation"]["evaluated"].get<std::size_t>());

  // A bad regions file: exit 2, one line naming the file and the problem, nothing inspected.
  std::ofstream(regions)
      << "regions:\n  - {name: root, boxes: [{min: [0, 0, 1], max: [1, 1, 0]}]}\n";
  const CliRun bad = runCli(args + " --regions " + regions);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(bad.out.empty());
  EXPECT_EQ(lineCount(bad.err), 1) << bad.err;
  EXPECT_NE(bad.err.find(regions), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("region 'root'"), std::string::npos) << bad.err;
  const CliRun missing = runCli(args + " --regions " + temp("no_such_regions.yaml"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("no_such_regions.yaml"), std::string::npos) << missing.err;
}

// Comparison points on the sample at its true pose (noise σ 0.02 mm): two CAD vertices read
// about nothing and pass, one held to ±0.1 µm fails the part; the JSON, the CSV table and the HTML
// report list each. A bad points file: exit 2, one line naming it.
TEST(Cli, ComparisonPointsAreReadJudgedAndReported) {
  const std::string points = temp("points.yaml");
  // Vertices of blade_fine.stl (mm) in metres, as --cad-scale 0.001 reads them.
  const Eigen::Vector3d span_25 =
      Eigen::Vector3d(-9.51298713684082f, 2.975978374481201f, 24.526315689086914f) * 0.001;
  const Eigen::Vector3d tip =
      Eigen::Vector3d(-2.507793664932251f, 0.5361624956130982f, 128.73684692382812f) * 0.001;
  const auto list = [](const Eigen::Vector3d& p) {
    char text[128];
    std::snprintf(text, sizeof(text), "[%.17g, %.17g, %.17g]", p.x(), p.y(), p.z());
    return std::string(text);
  };
  std::ofstream(points) << "points:\n"
                           "  - name: span_25\n"
                           "    position: "
                        << list(span_25)
                        << "\n"
                           "  - name: tip\n"
                           "    position: "
                        << list(tip)
                        << "\n"
                           "    radius: 0.003\n"
                           "  - name: tight\n"
                           "    position: "
                        << list(tip)
                        << "\n"
                           "    radius: 0.003\n"
                           "    tolerance: {upper: 0.0000001, lower: -0.0000001}\n";
  const std::string csv = temp("points_csv");
  const std::string html = temp("points.html");
  const std::string args = "--cad " + kBladeFine + " --cad-scale 0.001 --scan " + kScan +
                           " --tolerance 0.0002 --initial-pose " + poseArgument(sampleTruth());
  const CliRun run = runCli(args + " --points " + points + " --csv " + csv + " --html " + html);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  ASSERT_EQ(json["comparison_points"].size(), 3u);
  for (int p = 0; p < 2; ++p) {
    const nlohmann::json& point = json["comparison_points"][p];
    EXPECT_EQ(point["verdict"], "PASS") << point["verdict_reason"];
    EXPECT_LT(point["off_surface"].get<double>(), 1e-9);
    EXPECT_GE(point["points"].get<std::size_t>(), 3u);
    EXPECT_LT(std::abs(point["deviation"].get<double>()), 2e-5);  // σ / √n and the pose
    EXPECT_EQ(point["tolerance"]["upper"], 0.0002);
  }
  EXPECT_EQ(json["comparison_points"][1]["radius"], 0.003);
  const nlohmann::json& tight = json["comparison_points"][2];
  EXPECT_EQ(tight["verdict"], "FAIL");
  EXPECT_EQ(tight["deviation"], json["comparison_points"][1]["deviation"]);  // the same place
  EXPECT_EQ(json["verdict"], "FAIL");
  EXPECT_NE(json["verdict_reason"].get<std::string>().find("comparison point 'tight' fails"),
            std::string::npos)
      << json["verdict_reason"];
  namespace rt = freeform_inspection::report_test;
  const auto rows = rt::csvRows(slurp(csv + "/points.csv"));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].at("name"), "span_25");
  EXPECT_EQ(rows[2].at("verdict"), "FAIL");
  EXPECT_NEAR(std::stod(rows[0].at("deviation_mm")),
              json["comparison_points"][0]["deviation"].get<double>() * 1e3,
              1e-4);
  EXPECT_NEAR(std::stod(rows[0].at("nominal_z_mm")), span_25.z() * 1e3, 1e-4);
  const std::string page = slurp(html);
  EXPECT_NE(page.find("<h2>Comparison points</h2>"), std::string::npos);
  EXPECT_NE(page.find("<tr><th>tight</th><td>FAIL</td>"), std::string::npos);

  std::ofstream(points) << "points:\n  - {name: a, position: [0, 0, 0], radios: 0.001}\n";
  const CliRun bad = runCli(args + " --points " + points);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(bad.out.empty());
  EXPECT_EQ(lineCount(bad.err), 1) << bad.err;
  EXPECT_NE(bad.err.find(points), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("unknown key 'radios'"), std::string::npos) << bad.err;
}

// The shipped six-point nest (data/blade/blade_datums.yaml): the deviation is measured in the
// frame its targets fix, which on a scan of the CAD itself lies by the readings' noise from the
// best fit and the truth; five targets cannot fix a pose, and the part is then not evaluated.
TEST(Cli, DatumTargetsFixTheFrameTheDeviationIsMeasuredIn) {
  const std::string datums = std::string(FREEFORM_DATA_DIR) + "/blade/blade_datums.yaml";
  const std::string csv = temp("datums_csv");
  const std::string html = temp("datums.html");
  const std::string args = "--cad " + kBladeFine + " --cad-scale 0.001 --scan " + kScan +
                           " --tolerance 0.0002 --initial-pose " + poseArgument(sampleTruth());
  const CliRun run = runCli(args + " --points " + datums + " --csv " + csv + " --html " + html);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["verdict"], "PASS") << json["verdict_reason"];
  const nlohmann::json& alignment = json["datum_alignment"];
  ASSERT_TRUE(alignment.is_object());
  ASSERT_TRUE(alignment["aligned"].get<bool>()) << alignment["message"];
  ASSERT_EQ(alignment["targets"].size(), 6u);
  for (const nlohmann::json& target : alignment["targets"]) {
    EXPECT_GE(target["points"].get<std::size_t>(), 3u) << target["name"];
    EXPECT_LT(std::abs(target["deviation_aligned"].get<double>()), 1e-6) << target["name"];
    EXPECT_LT(std::abs(target["deviation_best_fit"].get<double>()), 5e-5) << target["name"];
  }
  EXPECT_GT(alignment["conditioning"].get<double>(), 0.02);
  EXPECT_EQ(alignment["precedence"], nlohmann::json({"A", "B", "C"}));
  // The readings' noise (σ 0.02 mm over 9-19 points each) moves the frame by hundredths of a
  // degree; a frame fixed by something else than the targets would not read them all as zero.
  const double moved = alignment["rotation_from_best_fit_deg"].get<double>();
  EXPECT_GT(moved, 0.0);
  EXPECT_LT(moved, 0.2);
  EXPECT_LT(turnDeg(reportedPose(json), sampleTruth()), 0.2);
  nlohmann::json best_fit;
  best_fit["transform_cad_from_scan"] = alignment["transform_cad_from_scan_best_fit"];
  EXPECT_LT(turnDeg(reportedPose(best_fit), sampleTruth()), 0.02);
  EXPECT_NEAR(turnDeg(reportedPose(best_fit), reportedPose(json)), moved, 1e-6);
  // The targets are comparison points too, read in the aligned frame.
  ASSERT_EQ(json["comparison_points"].size(), 6u);
  EXPECT_EQ(json["comparison_points"][0]["datum"], "A");
  EXPECT_EQ(json["comparison_points"][5]["deviation"],
            alignment["targets"][5]["deviation_aligned"]);
  namespace rt = freeform_inspection::report_test;
  const auto rows = rt::csvRows(slurp(csv + "/points.csv"));
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[3].at("datum"), "B");
  const std::string page = slurp(html);
  EXPECT_NE(page.find("<h2>Datum alignment</h2>"), std::string::npos);
  EXPECT_NE(page.find("<tr><th>C1</th><td>C</td>"), std::string::npos);
  EXPECT_NE(page.find("<p>T_cad_scan of the best fit:</p>"), std::string::npos);

  // Five targets: the pose stays the best fit's and the part is not evaluated.
  const std::string five = temp("five_datums.yaml");
  std::ofstream(five) << slurp(datums).substr(0, slurp(datums).find("  # C:"));
  const CliRun short_run = runCli(args + " --points " + five);
  ASSERT_EQ(short_run.exit_code, 0) << short_run.err;
  const nlohmann::json refused = nlohmann::json::parse(short_run.out);
  EXPECT_EQ(refused["verdict"], "NOT_EVALUATED");
  const std::string reason = refused["verdict_reason"];
  EXPECT_NE(reason.find("no datum alignment (5 datum target(s)"), std::string::npos) << reason;
  EXPECT_NE(reason.find("6 are needed"), std::string::npos) << reason;
  EXPECT_FALSE(refused["datum_alignment"]["aligned"].get<bool>());
  EXPECT_EQ(refused["transform_cad_from_scan"],
            refused["datum_alignment"]["transform_cad_from_scan_best_fit"]);
  EXPECT_EQ(refused["comparison_points"][0]["verdict"], "NOT_EVALUATED");

  // A fixed pose is the datum frame already: the targets are read as comparison points only.
  const CliRun fixed = runCli("--cad " + kBladeFine + " --cad-scale 0.001 --scan " + kScan +
                              " --tolerance 0.0002 --fixed-pose " + poseArgument(sampleTruth()) +
                              " --points " + datums);
  ASSERT_EQ(fixed.exit_code, 0) << fixed.err;
  const nlohmann::json at_fixed = nlohmann::json::parse(fixed.out);
  EXPECT_EQ(at_fixed["verdict"], "PASS") << at_fixed["verdict_reason"];
  EXPECT_FALSE(at_fixed["datum_alignment"]["aligned"].get<bool>());
  EXPECT_EQ(at_fixed["datum_alignment"]["message"],
            "not aligned: the fixed pose is the datum frame");
  EXPECT_EQ(at_fixed["comparison_points"][0]["verdict"], "PASS");
  EXPECT_NE(at_fixed["warnings"].dump().find("the datum targets do not move a fixed pose"),
            std::string::npos);

  // A precedence that leaves a target's datum out is refused before anything is loaded.
  const std::string unlisted = temp("unlisted_datum.yaml");
  std::string text = slurp(datums);
  text.replace(text.find("datum_precedence: [A, B, C]"), 27, "datum_precedence: [A, B]");
  std::ofstream(unlisted) << text;
  const CliRun bad = runCli(args + " --points " + unlisted);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(bad.out.empty());
  EXPECT_EQ(lineCount(bad.err), 1) << bad.err;
  EXPECT_NE(bad.err.find("comparison point 'C1': datum 'C' is not in datum_precedence"),
            std::string::npos)
      << bad.err;
}

// The sample scan is of the fine blade; blade.stl samples its superellipse platform half as
// densely, and its facets there lie up to 0.83 mm inside the exact outline (chord_error_test).
// Against it a good part fails with four bumps at the platform's ends; the result says that
// these may be the CAD's facets, and gives each region the chord error under it.
TEST(Cli, CoarseCadNamesItsChordErrorBesideTheDefectsItExplains) {
  const std::string args = "--cad " + kBlade + " --cad-scale 0.001 --scan " + kScan +
                           " --tolerance 0.0002 --no-model-cache";
  const CliRun run = runCli(args);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["verdict"], "FAIL");
  ASSERT_EQ(json["defects"].size(), 4u) << json["defects"];
  for (const nlohmann::json& region : json["defects"]) {
    const double peak = region["peak"].get<double>();
    const double chord = region["cad_chord_error"].get<double>();
    EXPECT_GT(peak, 5.5e-4);  // 0.62-0.64 mm
    EXPECT_GT(chord, 0.9 * peak);
    EXPECT_GT(std::abs(region["centroid"][0].get<double>()), 0.028);  // a platform end
  }
  const auto said = [&json](const std::string& text) {
    for (const nlohmann::json& warning : json["warnings"]) {
      if (warning.get<std::string>().find(text) != std::string::npos) {
        return true;
      }
    }
    return false;
  };
  EXPECT_TRUE(said("from the curved surface they stand for")) << json["warnings"];
  EXPECT_TRUE(said("4 of 4 defect region(s)")) << json["warnings"];
  // The fine mesh's chord error (0.33 mm at the same ends) is under a tenth of a 4 mm band.
  const CliRun fine = runCli("--cad " + kBladeFine + " --cad-scale 0.001 --scan " + kScan +
                             " --tolerance 0.004 --no-model-cache");
  ASSERT_EQ(fine.exit_code, 0) << fine.err;
  const nlohmann::json passed = nlohmann::json::parse(fine.out);
  EXPECT_EQ(passed["verdict"], "PASS");
  EXPECT_TRUE(passed["warnings"].empty()) << passed["warnings"];
}

// The CAD's descriptors and symmetries are kept between runs: the second run reads them and
// prints the same JSON but for the timings; a damaged cache file is said in the warnings and
// computed again; --no-model-cache writes none. A run that names no cache uses
// $XDG_CACHE_HOME (runCli points it into the test's own directory).
TEST(Cli, ModelCacheGivesTheSameResultAndADamagedFileIsComputedAgain) {
  const std::string cache = temp("model_cache");
  std::filesystem::remove_all(cache);
  const std::string args = "--cad " + kBlade + " --cad-scale 0.001 --scan " + kScan;
  const auto cacheFiles = [](const std::string& dir) {
    std::vector<std::filesystem::path> files;
    if (std::filesystem::exists(dir)) {
      for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        files.push_back(entry.path());
      }
    }
    return files;
  };
  const auto withoutTimings = [](const std::string& out) {
    nlohmann::json json = nlohmann::json::parse(out);
    json.erase("timings_s");
    return json;
  };
  const CliRun first = runCli(args + " --model-cache " + cache);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const std::vector<std::filesystem::path> files = cacheFiles(cache);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files.front().extension(), ".fimodel");
  const CliRun second = runCli(args + " --model-cache " + cache);
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_EQ(withoutTimings(second.out), withoutTimings(first.out));

  std::ofstream(files.front(), std::ios::trunc) << "damaged";
  const CliRun damaged = runCli(args + " --model-cache " + cache);
  ASSERT_EQ(damaged.exit_code, 0) << damaged.err;
  nlohmann::json json = withoutTimings(damaged.out);
  const nlohmann::json expected = withoutTimings(first.out);
  // The first warning says so; the others are the first run's (blade.stl's chord error).
  ASSERT_EQ(json["warnings"].size(), expected["warnings"].size() + 1) << json["warnings"];
  EXPECT_NE(json["warnings"][0].get<std::string>().find("computed again"), std::string::npos);
  json["warnings"].erase(0);
  EXPECT_EQ(json, expected);

  const std::string default_cache = kDefaultCache + "/freeform_inspection/models";
  std::filesystem::remove_all(kDefaultCache);
  ASSERT_EQ(runCli(args + " --no-model-cache").exit_code, 0);
  EXPECT_TRUE(cacheFiles(default_cache).empty());
  ASSERT_EQ(runCli(args).exit_code, 0);
  EXPECT_EQ(cacheFiles(default_cache).size(), 1u);
}

// A PCD scan is read by PCL through the module the core opens on the first PCD read. The same
// run from a copy of the program and its core library, with no module beside them: exit 2, one
// line that names the module, never a crash.
TEST(Cli, PcdScanReadThroughItsModuleAndAClearErrorWithoutIt) {
  const freeform_inspection::ScanLoadResult scan = freeform_inspection::loadScan(kScan, 1.0);
  ASSERT_TRUE(scan.status.ok()) << scan.status.message;
  const std::string pcd = temp("scan.pcd");
  ASSERT_TRUE(freeform_inspection::saveScanPcd(pcd, scan.scan).ok());
  const std::string args = "--cad " + kBlade + " --cad-scale 0.001 --scan " + pcd;
  const CliRun run = runCli(args);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["status"], "ok");

  namespace fs = std::filesystem;
  const fs::path alone = temp("without_module");
  fs::remove_all(alone);
  fs::create_directories(alone);
  const fs::path program = alone / fs::path(FREEFORM_CLI_PATH).filename();
  fs::copy_file(FREEFORM_CLI_PATH, program);
  fs::copy_file(FREEFORM_CORE_PATH, alone / fs::path(FREEFORM_CORE_PATH).filename());
  const std::string err_path = temp("alone_stderr.txt");
  const std::string command = "LD_LIBRARY_PATH=" + alone.string() +
                              " XDG_CACHE_HOME=" + kDefaultCache + " " + program.string() + " " +
                              args + " > /dev/null 2>" + err_path;
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  const std::string err = slurp(err_path);
  EXPECT_EQ(lineCount(err), 1) << err;
  EXPECT_NE(err.find("cannot load the PCD module"), std::string::npos) << err;
}

}  // namespace
