// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "freeform_inspection/config_fields.h"
#include "freeform_inspection/config_yaml.h"

#ifndef FREEFORM_DATA_DIR
#error "FREEFORM_DATA_DIR must name the package's data directory"
#endif

namespace freeform_inspection {
namespace {

const std::filesystem::path kConfigDir = std::filesystem::path(FREEFORM_DATA_DIR) / ".." / "config";

TEST(ConfigFiles, EveryShippedConfigParsesAndValidates) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kConfigDir)) {
    if (entry.path().extension() != ".yaml") {
      continue;
    }
    ++files;
    const ConfigLoadResult loaded = loadPipelineConfigFile(entry.path().string());
    EXPECT_TRUE(loaded.status.ok()) << entry.path() << ": " << loaded.status.message;
  }
  EXPECT_GE(files, 1) << "no config/*.yaml found in " << kConfigDir;
}

TEST(ConfigFiles, DefaultYamlStatesEveryFieldWithTheStructDefault) {
  // default.yaml documents the defaults; it must list every key, with the struct's value, so
  // the file a user copies cannot drift from the code.
  std::ifstream file(kConfigDir / "default.yaml");
  std::stringstream text;
  text << file.rdbuf();
  const ConfigLoadResult loaded = parsePipelineConfig(text.str());
  ASSERT_TRUE(loaded.status.ok()) << loaded.status.message;
  PipelineConfig from_file = loaded.config;
  PipelineConfig defaults;
  const auto file_fields = configFields(from_file);
  const auto default_fields = configFields(defaults);
  ASSERT_EQ(file_fields.size(), default_fields.size());
  for (std::size_t i = 0; i < file_fields.size(); ++i) {
    std::visit(
        [&](auto* value) {
          using T = std::remove_pointer_t<decltype(value)>;
          EXPECT_EQ(*value, *std::get<T*>(default_fields[i].target)) << file_fields[i].key;
        },
        file_fields[i].target);
    const std::string leaf = file_fields[i].key.substr(file_fields[i].key.find('/') + 1);
    EXPECT_NE(text.str().find("  " + leaf + ":"), std::string::npos)
        << "default.yaml does not list " << file_fields[i].key;
  }
}

TEST(ParsePipelineConfig, CropBoxIsAListOfSixNumbersWithEachMinimumBelowItsMaximum) {
  const ConfigLoadResult loaded =
      parsePipelineConfig("input: {crop_box: [-0.2, -0.2, 0.3, 0.2, 0.2, 1]}\n");
  ASSERT_TRUE(loaded.status.ok()) << loaded.status.message;
  EXPECT_EQ(loaded.config.input.crop_box, (std::vector<double>{-0.2, -0.2, 0.3, 0.2, 0.2, 1.0}));
  const ConfigLoadResult scalar = parsePipelineConfig("input: {crop_box: 0.5}\n");
  EXPECT_NE(scalar.status.message.find("'input/crop_box' has a value of the wrong type"),
            std::string::npos)
      << scalar.status.message;
  const ConfigLoadResult list_for_number = parsePipelineConfig("input: {max_points: [1, 2]}\n");
  EXPECT_NE(list_for_number.status.message.find("'input/max_points' has a value of the wrong"),
            std::string::npos)
      << list_for_number.status.message;
  for (const char* bad : {"input: {crop_box: [0, 0, 0, 1, 1]}\n",
                          "input: {crop_box: [0, 0, 0, 1, -1, 1]}\n",
                          "input: {crop_box: [0, 0, 0, 1, 1, .nan]}\n"}) {
    const ConfigLoadResult refused = parsePipelineConfig(bad);
    EXPECT_EQ(refused.status.code, StatusCode::kInvalidInput) << bad;
    EXPECT_NE(refused.status.message.find("input.crop_box"), std::string::npos)
        << bad << ": " << refused.status.message;
  }
}

TEST(ParsePipelineConfig, OverridesOnlyTheGivenKeys) {
  const ConfigLoadResult loaded = parsePipelineConfig("tolerance: {upper: 0.0005}\n");
  ASSERT_TRUE(loaded.status.ok()) << loaded.status.message;
  EXPECT_EQ(loaded.config.tolerance.upper, 0.0005);
  EXPECT_EQ(loaded.config.tolerance.lower, PipelineConfig().tolerance.lower);
}

TEST(ParsePipelineConfig, RefusesUnknownKeysWrongTypesAndInvalidValues) {
  const ConfigLoadResult misspelt = parsePipelineConfig("tolerance: {uper: 0.001}\n");
  EXPECT_EQ(misspelt.status.code, StatusCode::kInvalidInput);
  EXPECT_NE(misspelt.status.message.find("unknown key 'tolerance/uper'"), std::string::npos)
      << misspelt.status.message;
  const ConfigLoadResult wrong_type = parsePipelineConfig("input: {max_points: lots}\n");
  EXPECT_NE(wrong_type.status.message.find("'input/max_points' has a value of the wrong type"),
            std::string::npos)
      << wrong_type.status.message;
  const ConfigLoadResult negative = parsePipelineConfig("input: {max_points: -5}\n");
  EXPECT_EQ(negative.status.code, StatusCode::kInvalidInput);
  const ConfigLoadResult invalid = parsePipelineConfig("tolerance: {lower: 0.1}\n");
  EXPECT_NE(invalid.status.message.find("tolerance.lower"), std::string::npos);
  const ConfigLoadResult syntax = parsePipelineConfig("input: [unclosed\n");
  EXPECT_NE(syntax.status.message.find("YAML syntax error"), std::string::npos);
  EXPECT_EQ(loadPipelineConfigFile("/nonexistent.yaml").status.code, StatusCode::kInvalidInput);
}

}  // namespace
}  // namespace freeform_inspection
