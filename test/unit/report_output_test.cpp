// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// The CLI's report outputs on hand-built results: the deviation PLY (read back by the library's
// PLY reader and byte by byte), the PNG encoder, the point-splat renderer, the traceability
// hashes, the HTML report and the CSV tables.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "base64.h"
#include "deviation_ply.h"
#include "io_test_util.h"
#include "png_writer.h"
#include "report_csv.h"
#include "report_html.h"
#include "report_provenance.h"
#include "report_test_util.h"
#include "splat_renderer.h"
#include <gtest/gtest.h>

#include "freeform_inspection/content_hash.h"
#include "freeform_inspection/deviation_colours.h"
#include "freeform_inspection/io.h"

namespace fi = freeform_inspection;
namespace rt = freeform_inspection::report_test;

namespace {

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();

fi::ToleranceConfig tolerance02() {
  fi::ToleranceConfig tolerance;
  tolerance.upper = 0.0002;
  tolerance.lower = -0.0002;
  return tolerance;
}

// Four points, one unmatched (NaN), one in each defect, three in two named regions; two
// triangles.
fi::DeviationMap smallMap() {
  fi::DeviationMap map;
  map.points = {{0.001, 0.002, 0.003}, {0.1, 0.0, 0.0}, {0.0, 0.1, 0.0}, {-0.05, 0.025, 0.5}};
  map.deviation = {0.0f, 0.0005f, kNaNf, -0.001f};
  map.shape_deviation = {0.1f, kNaNf, 0.2f, 0.3f};
  map.defect = {-1, 0, -1, 1};
  map.region = {0, -1, 1, 0};
  return map;
}

const fi::Triangles kTwoFaces = {{0, 1, 2}, {0, 2, 3}};

template <typename T>
T littleEndian(const std::string& bytes, std::size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));  // the test host is little-endian (x86)
  return value;
}

TEST(DeviationPly, ReadsBackThroughTheLibraryReader) {
  fi::io_test::TempDir dir;
  const std::string path = dir.file("deviation.ply");
  const fi::DeviationMap map = smallMap();
  ASSERT_TRUE(fi::saveDeviationPly(path, map, kTwoFaces, tolerance02()).ok());
  const fi::ScanLoadResult loaded = fi::loadScan(path, 1.0);
  ASSERT_TRUE(loaded.status.ok()) << loaded.status.message;
  ASSERT_EQ(loaded.scan.points.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_LT((loaded.scan.points[i] - map.points[i]).norm(), 1e-7) << i;  // float precision
  }
  ASSERT_EQ(loaded.scan.faces.size(), 2u);
  EXPECT_EQ(loaded.scan.faces[1], Eigen::Vector3i(0, 2, 3));
}

TEST(DeviationPly, StoresEveryPropertyInTheDocumentedLayout) {
  fi::io_test::TempDir dir;
  const std::string path = dir.file("deviation.ply");
  const fi::DeviationMap map = smallMap();
  ASSERT_TRUE(fi::saveDeviationPly(path, map, kTwoFaces, tolerance02()).ok());
  const std::string bytes = fi::io_test::readBytes(path);
  const std::string end = "end_header\n";
  const std::size_t body = bytes.find(end) + end.size();
  const std::string header = bytes.substr(0, body);
  EXPECT_EQ(header.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  EXPECT_NE(header.find("\nelement vertex 4\n"), std::string::npos);
  EXPECT_NE(
      header.find(
          "property float x\nproperty float y\nproperty float z\nproperty float "
          "deviation\nproperty uchar in_tolerance\nproperty int defect\nproperty "
          "int region\nproperty float shape_deviation\nproperty uchar red\nproperty uchar green\n"
          "property uchar blue\nelement face 2\n"
          "property list uchar int vertex_indices\n"),
      std::string::npos)
      << header;
  constexpr std::size_t kVertexBytes = 32;
  ASSERT_EQ(bytes.size(), body + 4 * kVertexBytes + 2 * 13);
  for (std::size_t i = 0; i < 4; ++i) {
    const std::size_t at = body + i * kVertexBytes;
    EXPECT_FLOAT_EQ(littleEndian<float>(bytes, at + 8), static_cast<float>(map.points[i].z()));
    const float deviation = littleEndian<float>(bytes, at + 12);
    if (std::isnan(map.deviation[i])) {
      EXPECT_TRUE(std::isnan(deviation)) << i;
    } else {
      EXPECT_EQ(deviation, map.deviation[i]) << i;
    }
    EXPECT_EQ(static_cast<int>(bytes[at + 16]), i == 0 ? 1 : 0) << "in_tolerance " << i;
    EXPECT_EQ(littleEndian<std::int32_t>(bytes, at + 17), map.defect[i]) << i;
    EXPECT_EQ(littleEndian<std::int32_t>(bytes, at + 21), map.region[i]) << i;
    const float shape = littleEndian<float>(bytes, at + 25);
    EXPECT_TRUE(std::isnan(map.shape_deviation[i]) ? std::isnan(shape)
                                                   : shape == map.shape_deviation[i])
        << i;
    const fi::Rgb colour = fi::deviationColour(map.deviation[i], tolerance02());
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(static_cast<std::uint8_t>(bytes[at + 29 + c]), colour[c]) << i << " " << c;
    }
  }
  EXPECT_EQ(static_cast<std::uint8_t>(bytes[body + 4 * kVertexBytes]), 3u);
  EXPECT_EQ(littleEndian<std::int32_t>(bytes, body + 4 * kVertexBytes + 13 + 1 + 8), 3);
}

TEST(DeviationPly, CloudWithoutLabelsHasNoFacesAndDefaultLabels) {
  fi::io_test::TempDir dir;
  const std::string path = dir.file("cloud.ply");
  fi::DeviationMap map = smallMap();
  map.shape_deviation.clear();
  map.defect.clear();
  map.region.clear();
  ASSERT_TRUE(fi::saveDeviationPly(path, map, {}, tolerance02()).ok());
  const std::string bytes = fi::io_test::readBytes(path);
  EXPECT_EQ(bytes.find("element face"), std::string::npos);
  const std::size_t body = bytes.find("end_header\n") + 11;
  EXPECT_EQ(littleEndian<std::int32_t>(bytes, body + 17), -1);
  EXPECT_EQ(littleEndian<std::int32_t>(bytes, body + 21), -1);
  EXPECT_TRUE(std::isnan(littleEndian<float>(bytes, body + 25)));
  EXPECT_EQ(fi::loadScan(path, 1.0).scan.points.size(), 4u);
}

TEST(DeviationPly, RefusesInconsistentInputAndUnwritablePathsNamingTheFile) {
  fi::DeviationMap map = smallMap();
  const fi::Status bad_face = fi::saveDeviationPly("/tmp/x.ply", map, {{0, 1, 4}}, tolerance02());
  EXPECT_EQ(bad_face.code, fi::StatusCode::kInvalidInput);
  EXPECT_NE(bad_face.message.find("face 0 uses vertex 4 of 4"), std::string::npos)
      << bad_face.message;
  map.region.pop_back();
  const fi::Status short_regions = fi::saveDeviationPly("/tmp/x.ply", map, {}, tolerance02());
  EXPECT_NE(short_regions.message.find("3 region labels for 4 points"), std::string::npos)
      << short_regions.message;
  map.deviation.pop_back();
  const fi::Status short_map = fi::saveDeviationPly("/tmp/x.ply", map, {}, tolerance02());
  EXPECT_NE(short_map.message.find("3 deviations for 4 points"), std::string::npos)
      << short_map.message;
  const std::string nowhere = "/nonexistent_dir_ffi/deviation.ply";
  const fi::Status unwritable = fi::saveDeviationPly(nowhere, smallMap(), {}, tolerance02());
  EXPECT_EQ(unwritable.code, fi::StatusCode::kInvalidInput);
  EXPECT_NE(unwritable.message.find("cannot write deviation file '" + nowhere + "'"),
            std::string::npos)
      << unwritable.message;
}

TEST(PngWriter, WritesAValidRgbPngWithTheExactPixels) {
  fi::RgbImage image = fi::RgbImage::filled(7, 5, {255, 255, 255});
  image.set(0, 0, {1, 2, 3});
  image.set(6, 4, {200, 100, 50});
  const rt::PngInfo png = rt::readPng(fi::encodePng(image));
  ASSERT_TRUE(png.error.empty()) << png.error;
  EXPECT_EQ(png.width, 7);
  EXPECT_EQ(png.height, 5);
  ASSERT_EQ(png.rows.size(), 5u * (1 + 21));
  EXPECT_EQ(png.rows.substr(0, 4), std::string("\0\1\2\3", 4));  // filter byte, first pixel
  EXPECT_EQ(png.rows.substr(png.rows.size() - 3), "\xc8\x64\x32");
  EXPECT_TRUE(fi::encodePng(fi::RgbImage{}).empty());
}

TEST(Base64, EncodesTheRfc4648TestVectors) {
  EXPECT_EQ(fi::base64Encode(""), "");
  EXPECT_EQ(fi::base64Encode("f"), "Zg==");
  EXPECT_EQ(fi::base64Encode("fo"), "Zm8=");
  EXPECT_EQ(fi::base64Encode("foo"), "Zm9v");
  EXPECT_EQ(fi::base64Encode("foob"), "Zm9vYg==");
  EXPECT_EQ(fi::base64Encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(fi::dataUri("image/png", "\xff\xfe"), "data:image/png;base64,//4=");
}

TEST(ContentHash, MatchesXxh3ReferenceValues) {
  // The values `xxhsum -H3` (xxHash 0.8.1) prints for the same bytes.
  const fi::ContentHash empty;
  EXPECT_EQ(empty.hex(), "2d06800538d394c2");
  fi::ContentHash a;
  a.addText("a");
  EXPECT_EQ(a.value(), 0xe6c632b61e964e1full);
  fi::ContentHash foobar;
  foobar.addText("foo");
  foobar.addText("bar");  // incremental = all at once
  EXPECT_EQ(foobar.hex(), "d78fda63144c5c84");
  // Longer than XXH3's internal blocks, added in uneven pieces (one of them empty):
  // python3 -c "import sys; sys.stdout.buffer.write(bytes((i*7+3)%256 for i in range(5000)))"
  std::vector<unsigned char> bytes(5000);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    bytes[i] = static_cast<unsigned char>((i * 7 + 3) % 256);
  }
  fi::ContentHash pieces;
  std::size_t start = 0;
  for (const std::size_t piece :
       {std::size_t{1}, std::size_t{0}, std::size_t{250}, std::size_t{1999}}) {
    pieces.addBytes(bytes.data() + start, piece);
    start += piece;
  }
  pieces.addBytes(bytes.data() + start, bytes.size() - start);
  EXPECT_EQ(pieces.hex(), "799aaddd7339581d");
  fi::ContentHash whole;
  whole.addBytes(bytes.data(), bytes.size());
  EXPECT_EQ(whole.value(), pieces.value());
}

TEST(Provenance, ConfigHashFollowsEveryValueAndFileHashTheBytes) {
  fi::PipelineConfig config;
  const std::string original = fi::configHash(config);
  EXPECT_EQ(original.size(), 16u);
  EXPECT_EQ(fi::configHash(config), original);
  config.tolerance.upper = std::nextafter(0.0003, 1.0);  // one unit in the last place is seen
  fi::PipelineConfig other = config;
  other.tolerance.upper = 0.0003;
  EXPECT_NE(fi::configHash(config), fi::configHash(other));
  bool has_tolerance = false;
  for (const auto& [key, value] : fi::configEntries(other)) {
    has_tolerance |= key == "tolerance/upper" && value == "0.0003";
  }
  EXPECT_TRUE(has_tolerance) << "doubles print as their shortest exact text";

  fi::io_test::TempDir dir;
  fi::io_test::writeBytes(dir.file("scan.txt"), "a");
  EXPECT_EQ(fi::fileHash(dir.file("scan.txt")), "e6c632b61e964e1f");
  EXPECT_EQ(fi::fileHash(dir.file("missing.txt")), "unreadable");
  EXPECT_EQ(fi::utcTimestamp(0), "1970-01-01T00:00:00Z");
}

fi::Points grid(int nx, int ny, double spacing, double z) {
  fi::Points points;
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      points.emplace_back(i * spacing, j * spacing, z);
    }
  }
  return points;
}

TEST(SplatRenderer, FillsTheSurfaceAndKeepsTheNearestPoint) {
  // A red square in front of (z = 1) a larger blue one (z = 0), seen along -z.
  fi::Points points = grid(40, 40, 0.01, 0.0);
  std::vector<fi::Rgb> colours(points.size(), fi::Rgb{0, 0, 255});
  for (const Eigen::Vector3d& p : grid(10, 10, 0.01, 1.0)) {
    points.emplace_back(p + Eigen::Vector3d(0.15, 0.15, 0.0));
    colours.push_back({255, 0, 0});
  }
  fi::SplatConfig config;
  config.width = 100;
  config.height = 100;
  const fi::RgbImage image = fi::renderSplats(points, colours, fi::OrthoView{}, config);
  const auto pixel = [&](int x, int y) {
    const std::size_t at = static_cast<std::size_t>(y * image.width + x) * 3;
    return fi::Rgb{image.pixels[at], image.pixels[at + 1], image.pixels[at + 2]};
  };
  EXPECT_EQ(pixel(50, 50), (fi::Rgb{255, 0, 0})) << "the near square hides the far one";
  const fi::Rgb far = pixel(20, 20);  // blue, darkened by depth shading
  EXPECT_EQ(far[0], 0);
  EXPECT_EQ(far[2], static_cast<std::uint8_t>(std::lround(255 * (1.0 - config.depth_shading))));
  EXPECT_EQ(pixel(2, 2), config.background) << "margin stays empty";
  int holes = 0;  // splats sized to the spacing leave no background inside the square
  for (int y = 15; y < 85; ++y) {
    for (int x = 15; x < 85; ++x) {
      holes += pixel(x, y) == config.background ? 1 : 0;
    }
  }
  EXPECT_EQ(holes, 0);
}

TEST(SplatRenderer, PrincipalViewsFaceTheThinAxisOfAPlate) {
  fi::Points points;  // 0.4 x 0.1 x 0.01 m plate tilted in the CAD frame
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  for (const Eigen::Vector3d& p : grid(41, 11, 0.01, 0.0)) {
    points.push_back(rotation * Eigen::Vector3d(p.x(), p.y(), 0.0));
    points.push_back(rotation * Eigen::Vector3d(p.x(), p.y(), 0.01));
  }
  const std::vector<fi::OrthoView> views = fi::principalViews(points);
  ASSERT_EQ(views.size(), 3u);
  EXPECT_EQ(views[0].name, "front");
  const Eigen::Vector3d thin = rotation.col(2);
  EXPECT_NEAR(std::abs(views[0].axes.row(2).dot(thin)), 1.0, 1e-6);
  EXPECT_NEAR(std::abs(views[0].axes.row(0).dot(rotation.col(0))), 1.0, 1e-6) << "long axis right";
  EXPECT_NEAR(views[0].axes.row(2).dot(views[1].axes.row(2)), -1.0, 1e-9) << "back faces front";
  for (const fi::OrthoView& view : views) {
    EXPECT_NEAR((view.axes * view.axes.transpose() - Eigen::Matrix3d::Identity()).norm(), 0, 1e-9);
    EXPECT_NEAR(view.axes.determinant(), 1.0, 1e-9) << view.name;
  }
}

// A registered, failed part as the pipeline would report it.
fi::InspectionResult failedPart() {
  fi::InspectionResult result;
  result.registration = fi::RegistrationStatus::kOk;
  result.verdict = fi::Verdict::kFail;
  result.verdict_reason = "2 defect regions out of tolerance, peak +0.812 mm";
  result.rmse = 0.0000217;
  result.fitness = 0.93;
  result.score = 0.91;
  fi::DeviationStatistics& s = result.deviation;
  s.evaluated = 1600;
  s.unmatched = 12;
  s.mean = 0.0000123;
  s.std = 0.0000456;
  s.rms = 0.0000471;
  s.min = -0.000789;
  s.max = 0.000812;
  s.p95 = 0.000101;
  s.in_tolerance_fraction = 0.9731;
  s.coverage = 0.845;
  s.histogram_edges = {-0.0008, -0.0004, 0.0, 0.0004, 0.0008};
  s.histogram_counts = {10, 700, 850, 40};
  result.deviation_map.points = grid(40, 40, 0.001, 0.0);
  for (std::size_t i = 0; i < result.deviation_map.size(); ++i) {
    result.deviation_map.deviation.push_back(static_cast<float>((i % 40) * 0.00002 - 0.0004));
  }
  fi::DefectRegion bump;
  bump.sign = 1;
  bump.centroid = {0.0125, 0.0, 0.0};
  bump.points = 37;
  bump.area = 0.0000042;
  bump.peak = 0.000812;
  bump.mean = 0.00051;
  result.defects = {bump};
  result.warnings = {"scan <b>&</b> warning"};
  return result;
}

fi::ReportProvenance provenance() {
  fi::ReportProvenance p;
  p.cad_file = "data/blade/blade<1>.stl";
  p.scan_file = "scans/SN-42.ply";
  p.model_id = "cad";
  p.model_key = "0123456789abcdef";
  p.scan_hash = "fedcba9876543210";
  p.created = "2026-05-04T10:22:31Z";
  return p;
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++count;
  }
  return count;
}

TEST(HtmlReport, ShowsVerdictNumbersHistogramAndPictures) {
  fi::PipelineConfig config;
  config.tolerance = tolerance02();
  const std::string html = fi::renderHtmlReport(failedPart(), config, provenance());
  const std::string config_hash = fi::configHash(config);
  EXPECT_NE(html.find("class=\"verdict fail\""), std::string::npos);
  EXPECT_NE(html.find(">FAIL<"), std::string::npos);
  EXPECT_NE(html.find("2 defect regions out of tolerance, peak +0.812 mm"), std::string::npos);
  for (const char* shown : {"0.0123 mm",                // mean
                            "0.0456 mm",                // std
                            "-0.7890 mm",               // min
                            "0.8120 mm",                // max and defect peak
                            "97.3 %",                   // in tolerance
                            "84.5 %",                   // coverage
                            "1600 / 12",                // evaluated / unmatched
                            "0.0217 mm",                // rmse
                            "-0.2000 mm to 0.2000 mm",  // tolerance band
                            "fedcba9876543210",
                            "0123456789abcdef",
                            "2026-05-04T10:22:31Z",
                            config_hash.c_str(),
                            "scans/SN-42.ply",
                            "12.50, 0.00, 0.00",  // defect centroid [mm]
                            "4.200"}) {           // defect area [mm^2]
    EXPECT_NE(html.find(shown), std::string::npos) << shown;
  }
  EXPECT_NE(html.find("blade&lt;1&gt;.stl"), std::string::npos) << "file names are escaped";
  EXPECT_NE(html.find("scan &lt;b&gt;&amp;&lt;/b&gt; warning"), std::string::npos);
  // Histogram: one bar per bin, bins coloured by band, both tolerance lines.
  EXPECT_NE(html.find("<svg class=\"histogram\""), std::string::npos);
  EXPECT_EQ(occurrences(html, "<rect "), 4u);
  EXPECT_NE(html.find("fill=\"#3caf4b\""), std::string::npos) << "in-tolerance bins are green";
  EXPECT_EQ(occurrences(html, "stroke-dasharray"), 2u);
  // Three rendered views, each a valid PNG of the documented size.
  const std::vector<std::string> pngs = rt::dataUris(html, "image/png");
  ASSERT_EQ(pngs.size(), 3u);
  for (const std::string& bytes : pngs) {
    const rt::PngInfo png = rt::readPng(bytes);
    EXPECT_TRUE(png.error.empty()) << png.error;
    EXPECT_EQ(png.width, fi::SplatConfig().width);
    EXPECT_EQ(png.height, fi::SplatConfig().height);
  }
  EXPECT_NE(html.find("excess &gt;3x tolerance"), std::string::npos) << "legend";
  // Self-contained: nothing fetched, nothing run.
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
}

// With a measurement uncertainty the report shows the decision rule's zones; without, nothing.
TEST(HtmlReport, ShowsTheGuardBandsWhenAnUncertaintyIsStated) {
  fi::PipelineConfig config;
  config.tolerance = tolerance02();
  fi::InspectionResult result = failedPart();
  EXPECT_EQ(fi::renderHtmlReport(result, config, provenance()).find("Decision rule"),
            std::string::npos);
  fi::ConformanceZones& zones = result.conformance;
  zones.measurement_uncertainty = 0.00005;
  zones.acceptance_lower = -0.00015;
  zones.acceptance_upper = 0.00015;
  zones.rejection_lower = -0.00025;
  zones.rejection_upper = 0.00025;
  zones.regions_outside_acceptance = 3;
  zones.regions_beyond_rejection = 2;
  zones.inside_acceptance_fraction = 0.951;
  zones.inside_rejection_fraction = 0.987;
  const std::string html = fi::renderHtmlReport(result, config, provenance());
  for (const char* shown : {"Decision rule",
                            "ISO 14253-1",
                            "U = 0.0500 mm",
                            "-0.1500 mm to 0.1500 mm",
                            "-0.2500 mm to 0.2500 mm",
                            "3 / 2",
                            "95.1 % / 98.7 %"}) {
    EXPECT_NE(html.find(shown), std::string::npos) << shown;
  }
  zones.acceptance_lower = 0.0001;
  zones.acceptance_upper = -0.0001;
  EXPECT_NE(fi::renderHtmlReport(result, config, provenance()).find("empty (U is half the band"),
            std::string::npos);
}

TEST(HtmlReport, FailedRegistrationReportsWhyWithoutPictures) {
  fi::InspectionResult result;
  result.status = fi::Status::failure(fi::StatusCode::kRegistrationFailed, "no pose explains it");
  const std::string html = fi::renderHtmlReport(result, fi::PipelineConfig(), provenance());
  EXPECT_NE(html.find(">NOT_EVALUATED<"), std::string::npos);
  EXPECT_NE(html.find("no pose explains it"), std::string::npos) << "status message as reason";
  EXPECT_NE(html.find("No deviation map"), std::string::npos);
  EXPECT_NE(html.find("Not measured"), std::string::npos);
  EXPECT_EQ(html.find("data:image/png"), std::string::npos);
  EXPECT_EQ(html.find("<svg"), std::string::npos);
}

TEST(HtmlReport, UnwritablePathIsAStatusNamingTheFile) {
  const fi::Status status = fi::saveHtmlReport(
      "/nonexistent_dir_ffi/r.html", fi::InspectionResult(), fi::PipelineConfig(), provenance());
  EXPECT_EQ(status.code, fi::StatusCode::kInvalidInput);
  EXPECT_NE(status.message.find("cannot write HTML report '/nonexistent_dir_ffi/r.html': "),
            std::string::npos)
      << status.message;
}

// Table `file` of the tables as {column name: value} per row.
std::vector<std::map<std::string, std::string>> csvRows(const std::vector<fi::CsvTable>& tables,
                                                        const std::string& file) {
  for (const fi::CsvTable& table : tables) {
    if (table.file == file) {
      EXPECT_EQ(table.text.back(), '\n') << file;
      return rt::csvRows(table.text);
    }
  }
  ADD_FAILURE() << "no table " << file;
  return {};
}

TEST(CsvTables, HoldTheReportInMillimetresOneRowPerItem) {
  fi::PipelineConfig config;
  config.tolerance = tolerance02();
  fi::InspectionResult result = failedPart();
  fi::RegionResult root;
  root.name = "root \"A\", left";
  root.tolerance = tolerance02();
  root.verdict = fi::Verdict::kFail;
  root.verdict_reason = "1 defect region";
  root.deviation.evaluated = 200;
  root.deviation.max = 0.000812;
  root.deviation.coverage = 0.5;
  root.defects = 1;
  result.regions = {root};
  result.defects.front().region = 0;
  fi::ComparisonPointResult station;
  station.name = "LE, 50 %";
  station.nominal = {0.0125, -0.003, 0.0593};
  station.normal = {0.0, 1.0, 0.0};
  station.radius = 0.0016;
  station.tolerance = {0.00005, -0.00005};
  station.points = 14;
  station.deviation = 0.0000612;
  station.spread = 0.000018;
  station.verdict = fi::Verdict::kFail;
  station.verdict_reason = "deviation 0.0612 mm outside its band";
  fi::ComparisonPointResult unseen;  // not placed, not measured
  unseen.name = "TE";
  unseen.verdict_reason = "not evaluated: no CAD surface to place it on";
  result.comparison_points = {station, unseen};
  const std::vector<fi::CsvTable> tables = fi::renderCsvTables(result, config, provenance());
  ASSERT_EQ(tables.size(), 5u);

  const auto summary = csvRows(tables, "summary.csv");
  ASSERT_EQ(summary.size(), 1u);
  EXPECT_EQ(summary[0].at("created"), "2026-05-04T10:22:31Z");
  EXPECT_EQ(summary[0].at("scan_file"), "scans/SN-42.ply");
  EXPECT_EQ(summary[0].at("config_hash"), fi::configHash(config));
  EXPECT_EQ(summary[0].at("status"), "ok");
  EXPECT_EQ(summary[0].at("verdict"), "FAIL");
  EXPECT_EQ(summary[0].at("verdict_reason"), result.verdict_reason) << "a comma, quoted";
  EXPECT_EQ(summary[0].at("rmse_mm"), "0.0217");
  EXPECT_EQ(summary[0].at("lower_mm"), "-0.2000");
  EXPECT_EQ(summary[0].at("max_mm"), "0.8120");
  EXPECT_EQ(summary[0].at("min_mm"), "-0.7890");
  EXPECT_EQ(summary[0].at("points_evaluated"), "1600");
  EXPECT_EQ(summary[0].at("in_tolerance_fraction"), "0.973100");
  EXPECT_EQ(summary[0].at("defects"), "1");

  const auto defects = csvRows(tables, "defects.csv");
  ASSERT_EQ(defects.size(), 1u);
  EXPECT_EQ(defects[0].at("region"), root.name) << "quotes and a comma, quoted";
  EXPECT_EQ(defects[0].at("kind"), "excess");
  EXPECT_EQ(defects[0].at("points"), "37");
  EXPECT_EQ(defects[0].at("area_mm2"), "4.2000");
  EXPECT_EQ(defects[0].at("peak_mm"), "0.8120");
  EXPECT_EQ(defects[0].at("centroid_x_mm"), "12.5000");

  const auto histogram = csvRows(tables, "histogram.csv");
  ASSERT_EQ(histogram.size(), 4u);
  EXPECT_EQ(histogram[1].at("from_mm"), "-0.4000");
  EXPECT_EQ(histogram[1].at("to_mm"), "0.0000");
  EXPECT_EQ(histogram[1].at("points"), "700");

  const auto regions = csvRows(tables, "regions.csv");
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_EQ(regions[0].at("name"), root.name);
  EXPECT_EQ(regions[0].at("evaluated"), "true");
  EXPECT_EQ(regions[0].at("verdict"), "FAIL");
  EXPECT_EQ(regions[0].at("coverage"), "0.500000");
  EXPECT_EQ(regions[0].at("defects"), "1");

  const auto points = csvRows(tables, "points.csv");
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0].at("name"), station.name) << "a comma, quoted";
  EXPECT_EQ(points[0].at("verdict"), "FAIL");
  EXPECT_EQ(points[0].at("deviation_mm"), "0.0612");
  EXPECT_EQ(points[0].at("lower_mm"), "-0.0500");
  EXPECT_EQ(points[0].at("points"), "14");
  EXPECT_EQ(points[0].at("spread_mm"), "0.0180");
  EXPECT_EQ(points[0].at("nominal_x_mm"), "12.5000");
  EXPECT_EQ(points[0].at("nominal_z_mm"), "59.3000");
  EXPECT_EQ(points[0].at("radius_mm"), "1.6000");
  EXPECT_EQ(points[1].at("verdict"), "NOT_EVALUATED");
  EXPECT_EQ(points[1].at("deviation_mm"), "") << "unknown, not zero";
  EXPECT_EQ(points[1].at("nominal_x_mm"), "");
  EXPECT_EQ(points[1].at("verdict_reason"), unseen.verdict_reason);
  const std::string html = fi::renderHtmlReport(result, config, provenance());
  EXPECT_NE(html.find("<h2>Comparison points</h2>"), std::string::npos);
  EXPECT_NE(html.find("<tr><th>LE, 50 %</th><td>FAIL</td>"), std::string::npos);
}

TEST(CsvTables, NothingMeasuredLeavesTheNumbersEmptyAndTheHeadersInPlace) {
  fi::InspectionResult result;
  result.status = fi::Status::failure(fi::StatusCode::kRegistrationFailed, "no pose explains it");
  result.rmse = std::numeric_limits<double>::quiet_NaN();
  const std::vector<fi::CsvTable> tables =
      fi::renderCsvTables(result, fi::PipelineConfig(), provenance());
  const auto summary = csvRows(tables, "summary.csv");
  ASSERT_EQ(summary.size(), 1u);
  EXPECT_EQ(summary[0].at("status"), "failed");
  EXPECT_EQ(summary[0].at("verdict"), "NOT_EVALUATED");
  EXPECT_EQ(summary[0].at("rmse_mm"), "");
  EXPECT_EQ(summary[0].at("mean_mm"), "") << "not a perfect part's zero";
  EXPECT_EQ(summary[0].at("coverage"), "");
  EXPECT_EQ(summary[0].at("points_evaluated"), "0");
  for (const char* file : {"defects.csv", "histogram.csv", "regions.csv", "points.csv"}) {
    EXPECT_TRUE(csvRows(tables, file).empty()) << file;
  }
  for (const fi::CsvTable& table : tables) {
    EXPECT_EQ(std::count(table.text.begin(), table.text.end(), '\n'),
              table.file == "summary.csv" ? 2 : 1)
        << table.file;
  }
}

TEST(CsvTables, WrittenIntoADirectoryMadeForThemOrAStatusNamingIt) {
  fi::io_test::TempDir dir;
  const std::string target = dir.file("csv/part_1");
  ASSERT_TRUE(fi::saveCsvTables(target, failedPart(), fi::PipelineConfig(), provenance()).ok());
  for (const fi::CsvTable& table :
       fi::renderCsvTables(failedPart(), fi::PipelineConfig(), provenance())) {
    EXPECT_EQ(fi::io_test::readBytes(target + "/" + table.file), table.text) << table.file;
  }
  // Under a plain file no directory can be made.
  const std::string file = dir.file("plain");
  std::ofstream(file) << "x";
  const fi::Status status =
      fi::saveCsvTables(file + "/csv", failedPart(), fi::PipelineConfig(), provenance());
  EXPECT_EQ(status.code, fi::StatusCode::kInvalidInput);
  EXPECT_NE(status.message.find("cannot create CSV directory '" + file + "/csv'"),
            std::string::npos)
      << status.message;
}

}  // namespace
