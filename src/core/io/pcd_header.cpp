// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "pcd_header.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <string_view>
#include <vector>

#include "binary_util.h"
#include "text_util.h"
#include <Eigen/Core>

namespace freeform_inspection {
namespace io_internal {
namespace {

struct Keyword {
  const char* name;
  bool required;
};

// PCD v0.7 order. COLUMNS (older files) is read as FIELDS.
constexpr std::array<Keyword, 10> kKeywords = {{{"VERSION", false},
                                                {"FIELDS", true},
                                                {"SIZE", true},
                                                {"TYPE", true},
                                                {"COUNT", false},
                                                {"WIDTH", true},
                                                {"HEIGHT", true},
                                                {"VIEWPOINT", false},
                                                {"POINTS", true},
                                                {"DATA", true}}};
enum Key { kVersion, kFields, kSize, kType, kCount, kWidth, kHeight, kViewpoint, kPoints, kData };

bool isCommentOrBlank(const std::vector<std::string_view>& w) {
  return w.empty() || w[0].front() == '#';
}

// PCL compares only the start of the first word with its keywords, after DATA too.
bool pclWouldReadAsHeader(std::string_view word) {
  if (word.substr(0, 7) == "COLUMNS") {
    return true;
  }
  return std::any_of(kKeywords.begin(), kKeywords.end(), [word](const Keyword& k) {
    return word.substr(0, std::string_view(k.name).size()) == k.name;
  });
}

bool parseCount(std::string_view token, std::uint64_t max, std::uint64_t* value) {
  long long parsed = 0;
  if (!parseInteger(token, &parsed) || parsed < 0 || static_cast<std::uint64_t>(parsed) > max) {
    return false;
  }
  *value = static_cast<std::uint64_t>(parsed);
  return true;
}

class HeaderParser {
 public:
  explicit HeaderParser(const std::string& path) : path_(path) {}

  Status parse(PcdHeader* header) {
    std::ifstream file(path_, std::ios::binary);
    if (!file) {
      return Status::failure(StatusCode::kInvalidInput, "cannot read PCD '" + path_ + "'");
    }
    std::string line;
    while (std::getline(file, line)) {
      ++line_number_;
      offset_ += line.size() + (file.eof() ? 0 : 1);
      const std::vector<std::string_view> w = words(line);
      if (isCommentOrBlank(w)) {
        continue;
      }
      Status status = keywordLine(w, header);
      if (!status.ok() || last_ == kData) {
        return status.ok() ? afterData(&file) : status;
      }
    }
    return bad("no DATA line");
  }

 private:
  Status bad(const std::string& why) const {
    return Status::failure(StatusCode::kInvalidInput,
                           "cannot read PCD '" + path_ + "': header line " +
                               std::to_string(line_number_) + ": " + why);
  }

  Status keywordLine(const std::vector<std::string_view>& w, PcdHeader* header) {
    const std::string_view word = w[0] == "COLUMNS" ? "FIELDS" : w[0];
    const auto found = std::find_if(
        kKeywords.begin(), kKeywords.end(), [word](const Keyword& k) { return word == k.name; });
    if (found == kKeywords.end()) {
      return bad("unexpected '" + std::string(w[0]) + "'");
    }
    const int key = static_cast<int>(found - kKeywords.begin());
    if (key <= last_) {
      return bad("'" + std::string(w[0]) + "' repeated or out of order");
    }
    for (int k = last_ + 1; k < key; ++k) {
      if (kKeywords[static_cast<std::size_t>(k)].required) {
        return bad(std::string("no ") + kKeywords[static_cast<std::size_t>(k)].name + " before " +
                   found->name);
      }
    }
    last_ = key;
    return values(key, w, header);
  }

  Status values(int key, const std::vector<std::string_view>& w, PcdHeader* header) {
    const std::size_t n = w.size() - 1;
    const bool per_field = key == kSize || key == kType || key == kCount;
    if (per_field && n != fields_) {
      return bad(std::to_string(n) + " values for " + std::to_string(fields_) + " fields");
    }
    const bool single =
        key == kVersion || key == kWidth || key == kHeight || key == kPoints || key == kData;
    if ((single && n != 1) || (key == kFields && n == 0)) {
      return bad("wrong number of values");
    }
    constexpr std::uint64_t kMax32 = std::numeric_limits<std::uint32_t>::max();
    switch (key) {
      case kFields:
        fields_ = n;
        sizes_.assign(n, 4);
        counts_.assign(n, 1);
        break;
      case kSize:
        for (std::size_t i = 0; i < n; ++i) {
          if (!parseCount(w[i + 1], 8, &sizes_[i]) || (sizes_[i] & (sizes_[i] - 1)) != 0 ||
              sizes_[i] == 0) {
            return bad("SIZE must be 1, 2, 4 or 8, got '" + std::string(w[i + 1]) + "'");
          }
        }
        break;
      case kType:
        for (std::size_t i = 0; i < n; ++i) {
          const bool known = w[i + 1] == "I" || w[i + 1] == "U" || w[i + 1] == "F";
          if (!known || (w[i + 1] == "F" && sizes_[i] < 4)) {
            return bad("TYPE '" + std::string(w[i + 1]) + "' with SIZE " +
                       std::to_string(sizes_[i]));
          }
        }
        break;
      case kCount:
        for (std::size_t i = 0; i < n; ++i) {
          if (!parseCount(w[i + 1], std::numeric_limits<std::int32_t>::max(), &counts_[i]) ||
              counts_[i] == 0) {
            return bad("COUNT must be at least 1, got '" + std::string(w[i + 1]) + "'");
          }
        }
        break;
      case kWidth:
      case kHeight:
        if (!parseCount(w[1], kMax32, key == kWidth ? &width_ : &height_)) {
          return bad("expected a count, got '" + std::string(w[1]) + "'");
        }
        break;
      case kViewpoint:
        header->has_viewpoint = true;
        for (std::size_t i = 1; i < w.size(); ++i) {
          header->viewpoint += std::string(w[i]) + " ";
        }
        break;
      case kPoints:
        if (!parseCount(w[1], kMax32, &header->points) || header->points != width_ * height_) {
          return bad("POINTS '" + std::string(w[1]) + "' is not WIDTH " + std::to_string(width_) +
                     " x HEIGHT " + std::to_string(height_));
        }
        break;
      case kData:
        return data(w[1], header);
      default:
        break;
    }
    return Status::success();
  }

  Status data(std::string_view kind, PcdHeader* header) {
    if (kind == "ascii") {
      header->data = PcdHeader::Data::kAscii;
    } else if (kind == "binary") {
      header->data = PcdHeader::Data::kBinary;
    } else if (kind == "binary_compressed") {
      header->data = PcdHeader::Data::kBinaryCompressed;
    } else {
      return bad("unknown DATA '" + std::string(kind) + "'");
    }
    header->data_offset = offset_;
    header->values = 0;
    header->point_bytes = 0;
    for (std::size_t i = 0; i < fields_; ++i) {
      header->values += counts_[i];
      header->point_bytes += sizes_[i] * counts_[i];
    }
    return Status::success();
  }

  // PCL goes on reading lines after DATA as long as they look like header lines (blank and
  // comment lines included): a FIELDS or POINTS line there would redefine the cloud.
  Status afterData(std::ifstream* file) {
    std::string line;
    while (std::getline(*file, line)) {
      ++line_number_;
      const std::vector<std::string_view> w = words(line);
      if (isCommentOrBlank(w)) {
        continue;
      }
      if (pclWouldReadAsHeader(w[0])) {
        return bad("header keyword '" + std::string(w[0]) + "' after DATA");
      }
      break;
    }
    return Status::success();
  }

  const std::string& path_;
  int last_ = -1;  // index in kKeywords of the last keyword line
  std::size_t line_number_ = 0;
  std::uint64_t offset_ = 0;
  std::size_t fields_ = 0;
  std::vector<std::uint64_t> sizes_;
  std::vector<std::uint64_t> counts_;
  std::uint64_t width_ = 0;
  std::uint64_t height_ = 0;
};

}  // namespace

Status parsePcdHeader(const std::string& path, PcdHeader* header) {
  return HeaderParser(path).parse(header);
}

Status checkPcdDataSize(const std::string& path, const PcdHeader& header, std::uint64_t file_size) {
  const auto refuse = [&path](const std::string& why) {
    return Status::failure(StatusCode::kInvalidInput, "PCD '" + path + "' " + why);
  };
  const std::uint64_t available =
      file_size > header.data_offset ? file_size - header.data_offset : 0;
  const std::uint64_t points = header.points;
  const std::uint64_t step = header.point_bytes;
  const std::string declared =
      "declares " + std::to_string(points) + " points of " + std::to_string(step) + " bytes";
  const std::string only = " but only " + std::to_string(available) + " bytes follow the header";
  switch (header.data) {
    case PcdHeader::Data::kAscii:
      // Every value is at least a character and a separator (none after the last).
      return header.values != 0 && points > (available + 1) / 2 / header.values
                 ? refuse(declared + " with " + std::to_string(header.values) +
                          " ascii values each" + only)
                 : Status::success();
    case PcdHeader::Data::kBinary:
      return step != 0 && points > available / step ? refuse(declared + only) : Status::success();
    case PcdHeader::Data::kBinaryCompressed:
      break;
  }
  if (points == 0) {
    return Status::success();
  }
  // uint32 compressed and uncompressed sizes, then LZF data; an LZF token of 3 bytes expands to
  // at most 264, hence the ratio 88.
  constexpr std::uint64_t kMaxLzfRatio = 88;
  char sizes[8] = {};
  std::ifstream file(path, std::ios::binary);
  file.seekg(static_cast<std::streamoff>(header.data_offset));
  if (available < sizeof(sizes) || !file.read(sizes, sizeof(sizes))) {
    return refuse(declared + " as binary_compressed" + only);
  }
  const std::uint64_t compressed = loadScalar<std::uint32_t>(sizes, true);
  const std::uint64_t uncompressed = loadScalar<std::uint32_t>(sizes + 4, true);
  const bool matches = step != 0 && points <= std::numeric_limits<std::uint32_t>::max() / step &&
                       uncompressed == points * step;
  if (!matches || compressed > available - sizeof(sizes) ||
      uncompressed > kMaxLzfRatio * compressed) {
    return refuse(declared + " but its binary_compressed data holds " +
                  std::to_string(uncompressed) + " bytes compressed into " +
                  std::to_string(compressed) + ", with " + std::to_string(available) +
                  " bytes after the header");
  }
  return Status::success();
}

std::string pcdViewpointWarning(const PcdHeader& header) {
  if (!header.has_viewpoint) {
    return "";
  }
  double v[7] = {};
  std::size_t pos = 0;
  std::string_view token;
  int parsed = 0;
  while (parsed < 7 && nextToken(header.viewpoint, &pos, &token) &&
         parseDouble(token, &v[parsed])) {
    ++parsed;
  }
  if (parsed < 7) {
    return "PCD VIEWPOINT is malformed; it is ignored (points are used as stored)";
  }
  // Eigen's isZero / isApprox tolerance in float: translation 0, rotation (w, x, y, z) = (1, 0,
  // 0, 0).
  constexpr double kPrecision = 1e-5;
  const Eigen::Vector4d rotation(v[3], v[4], v[5], v[6]);
  const bool identity = std::fabs(v[0]) <= kPrecision && std::fabs(v[1]) <= kPrecision &&
                        std::fabs(v[2]) <= kPrecision &&
                        (rotation - Eigen::Vector4d(1, 0, 0, 0)).norm() <=
                            kPrecision * std::min(rotation.norm(), 1.0);
  return identity ? ""
                  : "PCD VIEWPOINT is not the identity; it is ignored (points are used as stored)";
}

}  // namespace io_internal
}  // namespace freeform_inspection
