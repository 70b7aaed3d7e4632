// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "cloud_conversion.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>

namespace freeform_inspection_ros {
namespace {

using sensor_msgs::PointField;

struct FieldReader {
  std::uint32_t offset = 0;
  std::uint8_t datatype = PointField::FLOAT32;

  double read(const std::uint8_t* point) const {
    if (datatype == PointField::FLOAT64) {
      double value;
      std::memcpy(&value, point + offset, sizeof(value));
      return value;
    }
    float value;
    std::memcpy(&value, point + offset, sizeof(value));
    return static_cast<double>(value);
  }
};

std::optional<FieldReader> findField(const sensor_msgs::PointCloud2& cloud,
                                     const std::string& name,
                                     std::string* error) {
  const auto copies =
      std::count_if(cloud.fields.begin(), cloud.fields.end(), [&name](const PointField& field) {
        return field.name == name;
      });
  if (copies > 1) {  // which one is the coordinate would be a guess
    *error = "field '" + name + "' appears " + std::to_string(copies) + " times";
    return std::nullopt;
  }
  for (const auto& field : cloud.fields) {
    if (field.name != name) {
      continue;
    }
    const std::uint32_t size = field.datatype == PointField::FLOAT64 ? 8 : 4;
    if (field.datatype != PointField::FLOAT32 && field.datatype != PointField::FLOAT64) {
      *error = "field '" + name + "' has datatype " + std::to_string(field.datatype) +
               "; only FLOAT32 (7) and FLOAT64 (8) coordinates are supported";
    } else if (std::uint64_t{field.offset} + size > cloud.point_step) {  // no wrap-around
      *error = "field '" + name + "' at offset " + std::to_string(field.offset) +
               " does not fit in point_step " + std::to_string(cloud.point_step);
    } else {
      return FieldReader{field.offset, field.datatype};
    }
    return std::nullopt;
  }
  *error = "cloud has no '" + name + "' field";
  return std::nullopt;
}

std::string checkLayout(const sensor_msgs::PointCloud2& cloud) {
  const std::uint64_t row_bytes = std::uint64_t{cloud.width} * cloud.point_step;
  if (cloud.is_bigendian) {
    return "big-endian clouds are not supported";
  }
  if (cloud.row_step < row_bytes) {
    return "row_step " + std::to_string(cloud.row_step) + " < width " +
           std::to_string(cloud.width) + " * point_step " + std::to_string(cloud.point_step);
  }
  if (cloud.data.size() < std::uint64_t{cloud.row_step} * cloud.height) {
    return "data holds " + std::to_string(cloud.data.size()) + " bytes, less than row_step " +
           std::to_string(cloud.row_step) + " * height " + std::to_string(cloud.height);
  }
  return "";
}

}  // namespace

CloudConversion cloudToScan(const sensor_msgs::PointCloud2& cloud) {
  CloudConversion result;
  std::string error = checkLayout(cloud);
  std::optional<FieldReader> x;
  std::optional<FieldReader> y;
  std::optional<FieldReader> z;
  if (error.empty() && (x = findField(cloud, "x", &error)) && (y = findField(cloud, "y", &error)) &&
      (z = findField(cloud, "z", &error))) {
    if (cloud.width == 0 || cloud.height == 0) {
      // No points, no grid; and no loop over up to 2^32 empty rows (found by fuzz_cloud).
      return result;
    }
    result.scan.points.reserve(std::size_t{cloud.width} * cloud.height);
    if (cloud.height > 1) {  // a range image: the pipeline triangulates it on its grid
      result.scan.width = static_cast<int>(cloud.width);
      result.scan.height = static_cast<int>(cloud.height);
    }
    for (std::uint32_t row = 0; row < cloud.height; ++row) {
      const std::uint8_t* row_data = cloud.data.data() + std::size_t{row} * cloud.row_step;
      for (std::uint32_t col = 0; col < cloud.width; ++col) {
        const std::uint8_t* point = row_data + std::size_t{col} * cloud.point_step;
        result.scan.points.emplace_back(x->read(point), y->read(point), z->read(point));
      }
    }
    return result;
  }
  result.status =
      fi::Status::failure(fi::StatusCode::kInvalidInput, "invalid PointCloud2: " + error);
  return result;
}

}  // namespace freeform_inspection_ros
