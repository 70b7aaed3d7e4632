// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// ~load_model's file policy: only regular files inside the configured model directories, after
// resolving "..", "." and symbolic links; size capped.
#include "model_access.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

namespace freeform_inspection_ros {
namespace {

namespace fs = std::filesystem;

class ModelAccess : public testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("fi_model_access_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "models" / "sub");
    fs::create_directories(root_ / "secret");
    write(root_ / "models" / "part.stl", 100);
    write(root_ / "models" / "sub" / "big.stl", 3 * 1024 * 1024);
    write(root_ / "secret" / "key.stl", 10);
    fs::create_symlink(root_ / "secret" / "key.stl", root_ / "models" / "escape.stl");
    fs::create_symlink(root_ / "models" / "part.stl", root_ / "secret" / "into_models.stl");
  }
  void TearDown() override { fs::remove_all(root_); }

  static void write(const fs::path& path, std::size_t bytes) {
    std::ofstream file(path, std::ios::binary);
    file << std::string(bytes, 'x');
  }
  std::string at(const std::string& relative) const { return (root_ / relative).string(); }
  std::vector<std::string> dirs() const { return {at("models")}; }

  fs::path root_;
};

constexpr std::uintmax_t kMiB = 1024 * 1024;

TEST_F(ModelAccess, FilesInsideTheDirectoriesAreAllowed) {
  EXPECT_EQ(checkModelAccess(at("models/part.stl"), dirs(), kMiB), "");
  EXPECT_EQ(checkModelAccess(at("models/sub/../part.stl"), dirs(), kMiB), "");
  // A link from outside that points in is judged by its target.
  EXPECT_EQ(checkModelAccess(at("secret/into_models.stl"), dirs(), kMiB), "");
}

TEST_F(ModelAccess, EscapesAreRefusedNamingThePath) {
  for (const std::string& escape : {at("models/../secret/key.stl"),
                                    at("models/escape.stl"),  // symlink pointing outside
                                    at("secret/key.stl")}) {
    const std::string reason = checkModelAccess(escape, dirs(), kMiB);
    EXPECT_NE(reason.find("outside the model directories"), std::string::npos) << escape;
    EXPECT_NE(reason.find(escape), std::string::npos) << reason;
  }
  // A directory name that only starts like an allowed one is not inside it.
  fs::create_directories(root_ / "models_evil");
  write(root_ / "models_evil" / "x.stl", 10);
  EXPECT_NE(checkModelAccess(at("models_evil/x.stl"), dirs(), kMiB), "");
  EXPECT_NE(checkModelAccess(at("models/part.stl"), {}, kMiB), "") << "no directory, no access";
}

TEST_F(ModelAccess, MissingFilesDirectoriesAndOversizedFilesAreRefused) {
  EXPECT_NE(checkModelAccess(at("models/none.stl"), dirs(), kMiB).find("cannot open"),
            std::string::npos);
  EXPECT_NE(checkModelAccess(at("models/sub"), dirs(), kMiB).find("not a regular file"),
            std::string::npos);
  const std::string big = checkModelAccess(at("models/sub/big.stl"), dirs(), 2 * kMiB);
  EXPECT_NE(big.find("3145728 bytes"), std::string::npos) << big;
  EXPECT_EQ(checkModelAccess(at("models/sub/big.stl"), dirs(), 4 * kMiB), "");
}

}  // namespace
}  // namespace freeform_inspection_ros
