// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// The node's report archive (src/ros/report_files.cpp, ~report_dir): file names that a request's
// part id cannot steer outside the directory, and the files actually written. No ROS master.
#include "report_files.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "report_test_util.h"
#include <gtest/gtest.h>

#include "freeform_inspection/model.h"

namespace freeform_inspection_ros {
namespace {

namespace fs = std::filesystem;

std_msgs::Header stampedHeader() {
  std_msgs::Header header;
  header.frame_id = "scanner";
  header.stamp = ros::Time(1234, 500000000);
  return header;
}

TEST(ReportFiles, BaseNameKeepsSafeCharactersAndTheStamp) {
  EXPECT_EQ(reportBaseName("SN-42_a.b", stampedHeader()), "SN-42_a.b_1234.500000000");
  EXPECT_EQ(reportBaseName("", stampedHeader()), "inspection_1234.500000000");
}

TEST(ReportFiles, PartIdCannotNameAPathOutsideTheDirectory) {
  const std::vector<std::string> hostiles = {"../../etc/passwd",
                                             "/abs/path",
                                             "..",
                                             ".hidden",
                                             "a/../b",
                                             "x\\y",
                                             std::string("nul\0byte", 8),
                                             "tab\tnew\nline"};
  for (const std::string& hostile : hostiles) {
    const std::string base = reportBaseName(hostile, stampedHeader());
    EXPECT_EQ(base.find('/'), std::string::npos) << base;
    EXPECT_EQ(base.find('\\'), std::string::npos) << base;
    EXPECT_NE(base.front(), '.') << base;
    EXPECT_EQ(fs::path(base).filename().string(), base) << "one path component";
    for (const char c : base) {
      EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_' ||
                  c == '.')
          << base;
    }
  }
}

TEST(ReportFiles, WritesTheHtmlOfAnUnregisteredScanAndNoDeviationFile) {
  const auto loaded = freeform_inspection::loadModel(
      std::string(FREEFORM_TEST_DATA_DIR) + "/cube_ascii.stl", 1.0, "cube");
  ASSERT_TRUE(loaded.status.ok()) << loaded.status.message;
  const fs::path dir = fs::temp_directory_path() / "freeform_report_files_test" / "new";
  fs::remove_all(dir.parent_path());
  freeform_inspection::InspectionResult result;  // registration failed: no deviation map
  ReportSource source;
  source.part_id = "../SN-7";
  source.model_path = "cube_ascii.stl";
  source.scan_name = "Inspect request";
  source.scan_hash = "0123456789abcdef";
  const ReportFilesResult written = writeReportFiles(dir.string(),
                                                     result,
                                                     freeform_inspection::PipelineConfig{},
                                                     *loaded.model,
                                                     source,
                                                     stampedHeader());
  EXPECT_TRUE(written.error.empty()) << written.error;
  ASSERT_EQ(written.files.size(), 2u);
  const fs::path html(written.files.front());
  EXPECT_TRUE(html.is_absolute());
  EXPECT_EQ(html.parent_path(), fs::absolute(dir)) << "created, and nothing outside it";
  EXPECT_EQ(html.filename().string(), "_._SN-7_1234.500000000.html");
  std::ifstream file(html);
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("0123456789abcdef"), std::string::npos) << "the scan hash is on record";
  EXPECT_NE(text.find("<td>../SN-7</td>"), std::string::npos) << "the part id as given";

  // One line per inspection in inspections.csv, under one header.
  const fs::path log(written.files.back());
  EXPECT_EQ(log, fs::absolute(dir) / "inspections.csv");
  result.verdict_reason = "second, with a comma";
  ASSERT_TRUE(writeReportFiles(dir.string(),
                               result,
                               freeform_inspection::PipelineConfig{},
                               *loaded.model,
                               source,
                               stampedHeader())
                  .error.empty());
  std::ifstream csv(log);
  const std::string lines((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  const auto rows = freeform_inspection::report_test::csvRows(lines);
  ASSERT_EQ(rows.size(), 2u) << lines;
  EXPECT_EQ(rows[0].at("part_id"), "../SN-7");
  EXPECT_EQ(rows[0].at("verdict"), "NOT_EVALUATED");
  EXPECT_EQ(rows[0].at("scan_hash"), "0123456789abcdef");
  EXPECT_EQ(rows[1].at("verdict_reason"), "second, with a comma");

  // Another version's header: nothing is appended, and the error names the file.
  std::ofstream(log) << "created,verdict\n";
  const ReportFilesResult refused = writeReportFiles(dir.string(),
                                                     result,
                                                     freeform_inspection::PipelineConfig{},
                                                     *loaded.model,
                                                     source,
                                                     stampedHeader());
  EXPECT_NE(refused.error.find("cannot append to CSV summary '" + log.string() + "'"),
            std::string::npos)
      << refused.error;
  std::ifstream old_log(log);
  EXPECT_EQ(
      std::string((std::istreambuf_iterator<char>(old_log)), std::istreambuf_iterator<char>()),
      "created,verdict\n");
  fs::remove_all(dir.parent_path());
}

TEST(ReportFiles, UncreatableDirectoryIsAnErrorNotACrash) {
  const fs::path blocker = fs::temp_directory_path() / "freeform_report_files_blocker";
  std::ofstream(blocker) << "a file where the directory should be";
  const auto loaded = freeform_inspection::loadModel(
      std::string(FREEFORM_TEST_DATA_DIR) + "/cube_ascii.stl", 1.0, "cube");
  ASSERT_TRUE(loaded.status.ok()) << loaded.status.message;
  const ReportFilesResult written = writeReportFiles((blocker / "reports").string(),
                                                     freeform_inspection::InspectionResult{},
                                                     freeform_inspection::PipelineConfig{},
                                                     *loaded.model,
                                                     ReportSource{},
                                                     stampedHeader());
  EXPECT_TRUE(written.files.empty());
  EXPECT_NE(written.error.find("cannot create ~report_dir"), std::string::npos) << written.error;
  fs::remove(blocker);
}

}  // namespace
}  // namespace freeform_inspection_ros
