// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "fuzz_cloud_entry.h"

#include <array>
#include <string>
#include <vector>

#include "cloud_conversion.h"

namespace freeform_inspection {
namespace fuzz {
namespace {

using sensor_msgs::PointField;

// Reads the fuzz bytes front to back; past the end every read is 0.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }

  std::uint32_t word() {
    std::uint32_t value = 0;
    for (int i = 0; i < 4; ++i) {
      value |= std::uint32_t{byte()} << (8 * i);
    }
    return value;
  }

  std::uint32_t size() {
    const std::uint8_t b = byte();
    return b < 0x80 ? b : word();
  }

  std::vector<std::uint8_t> rest() {
    std::vector<std::uint8_t> bytes(data_ + pos_, data_ + size_);
    pos_ = size_;
    return bytes;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

std::string fieldName(ByteReader* reader) {
  static const std::array<const char*, 7> kNames = {
      "x", "y", "z", "rgb", "intensity", "normal_x", ""};
  const std::size_t choice = reader->byte() % (kNames.size() + 1);
  if (choice < kNames.size()) {
    return kNames[choice];
  }
  std::string name(reader->byte() % 8, ' ');
  for (char& c : name) {
    c = static_cast<char>(reader->byte());
  }
  return name;
}

}  // namespace

sensor_msgs::PointCloud2 decodeCloud(const std::uint8_t* data, std::size_t size) {
  ByteReader reader(data, size);
  sensor_msgs::PointCloud2 cloud;
  const std::uint8_t flags = reader.byte();
  cloud.is_bigendian = (flags & 1) != 0;
  cloud.is_dense = (flags & 2) != 0;
  cloud.width = reader.size();
  cloud.height = reader.size();
  cloud.point_step = reader.size();
  const auto packed = static_cast<std::uint32_t>(std::uint64_t{cloud.width} * cloud.point_step);
  switch ((flags >> 2) & 3) {
    case 0:
      cloud.row_step = packed;
      break;
    case 1:
      cloud.row_step = static_cast<std::uint32_t>(std::uint64_t{packed} + reader.byte());
      break;
    default:
      cloud.row_step = reader.size();
      break;
  }
  const int fields = reader.byte() % 9;
  for (int i = 0; i < fields; ++i) {
    PointField field;
    field.name = fieldName(&reader);
    field.offset = reader.size();
    field.datatype = reader.byte();
    field.count = reader.size();
    cloud.fields.push_back(field);
  }
  cloud.data = reader.rest();
  return cloud;
}

EntryOutcome fuzzCloud(const std::uint8_t* data, std::size_t size) {
  const sensor_msgs::PointCloud2 cloud = decodeCloud(data, size);
  const freeform_inspection_ros::CloudConversion result =
      freeform_inspection_ros::cloudToScan(cloud);
  EntryOutcome outcome;
  outcome.ok = result.status.ok();
  outcome.message = result.status.message;
  const Scan& scan = result.scan;
  if (!outcome.ok) {
    if (outcome.message.empty()) {
      markBroken(&outcome, "failure without a message");
    }
    if (!scan.points.empty()) {
      markBroken(&outcome, "refused cloud with points");
    }
    return outcome;
  }
  if (scan.points.size() != std::uint64_t{cloud.width} * cloud.height) {
    markBroken(&outcome, "point count is not width * height");
  }
  const bool grid = cloud.height > 1 && cloud.width > 0;  // an empty cloud has no grid
  if (grid && (static_cast<std::int64_t>(scan.width) != cloud.width ||
               static_cast<std::int64_t>(scan.height) != cloud.height)) {
    markBroken(&outcome, "grid size differs from the cloud's");
  }
  if (!grid && (scan.width != 0 || scan.height != 0)) {
    markBroken(&outcome, "unorganized cloud with a grid");
  }
  return outcome;
}

}  // namespace fuzz
}  // namespace freeform_inspection
