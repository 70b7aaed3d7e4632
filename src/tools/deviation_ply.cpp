// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "deviation_ply.h"

#include <cstdint>
#include <cstring>
#include <limits>

#include "file_output.h"

#include "freeform_inspection/deviation_colours.h"

namespace freeform_inspection {
namespace {

constexpr char kWhat[] = "deviation file";

Status invalid(const std::string& path, const std::string& why) {
  return Status::failure(StatusCode::kInvalidInput,
                         std::string("cannot write ") + kWhat + " '" + path + "': " + why);
}

// Byte order is fixed by the header ("binary_little_endian"), whatever the host's.
template <typename T>
void appendLittleEndian(std::string* out, T value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    const std::size_t index = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ ? i : sizeof(T) - 1 - i;
    out->push_back(static_cast<char>(bytes[index]));
  }
}

std::string header(std::size_t vertices, std::size_t faces) {
  std::string text =
      "ply\nformat binary_little_endian 1.0\ncomment freeform_inspection deviation map, CAD "
      "frame, metres\ncomment deviation NaN = no CAD surface near the point\nelement vertex " +
      std::to_string(vertices) +
      "\nproperty float x\nproperty float y\nproperty float z\nproperty float deviation\n"
      "property uchar in_tolerance\nproperty int defect\nproperty int region\n"
      "property float shape_deviation\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (faces > 0) {
    text += "element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\n";
  }
  return text + "end_header\n";
}

// Sizes and face indices, checked before anything is written.
std::string inconsistency(const DeviationMap& map, const Triangles& faces) {
  const std::size_t n = map.points.size();
  if (map.deviation.size() != n) {
    return std::to_string(map.deviation.size()) + " deviations for " + std::to_string(n) +
           " points";
  }
  if (!map.shape_deviation.empty() && map.shape_deviation.size() != n) {
    return std::to_string(map.shape_deviation.size()) + " shape deviations for " +
           std::to_string(n) + " points";
  }
  if (!map.defect.empty() && map.defect.size() != n) {
    return std::to_string(map.defect.size()) + " defect labels for " + std::to_string(n) +
           " points";
  }
  if (!map.region.empty() && map.region.size() != n) {
    return std::to_string(map.region.size()) + " region labels for " + std::to_string(n) +
           " points";
  }
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    return "too many points for int face indices";
  }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      if (faces[f][c] < 0 || static_cast<std::size_t>(faces[f][c]) >= n) {
        return "face " + std::to_string(f) + " uses vertex " + std::to_string(faces[f][c]) +
               " of " + std::to_string(n);
      }
    }
  }
  return "";
}

void appendVertex(std::string* out,
                  const DeviationMap& map,
                  std::size_t i,
                  const ToleranceBands& bands) {
  const ToleranceConfig& tolerance = bands.at(i);
  for (int axis = 0; axis < 3; ++axis) {
    appendLittleEndian(out, static_cast<float>(map.points[i][axis]));
  }
  const float deviation = map.deviation[i];
  appendLittleEndian(out, deviation);
  appendLittleEndian(out, static_cast<std::uint8_t>(inTolerance(deviation, tolerance) ? 1 : 0));
  appendLittleEndian(out, static_cast<std::int32_t>(map.defect.empty() ? -1 : map.defect[i]));
  appendLittleEndian(out, static_cast<std::int32_t>(map.region.empty() ? -1 : map.region[i]));
  appendLittleEndian(out,
                     map.shape_deviation.empty() ? std::numeric_limits<float>::quiet_NaN()
                                                 : map.shape_deviation[i]);
  for (const std::uint8_t channel : deviationColour(deviation, tolerance)) {
    appendLittleEndian(out, channel);
  }
}

}  // namespace

Status saveDeviationPly(const std::string& path,
                        const DeviationMap& map,
                        const Triangles& faces,
                        const ToleranceBands& tolerance) {
  const std::string problem = inconsistency(map, faces);
  if (!problem.empty()) {
    return invalid(path, problem);
  }
  std::string bytes = header(map.size(), faces.size());
  bytes.reserve(bytes.size() + 32 * map.size() + 13 * faces.size());
  for (std::size_t i = 0; i < map.size(); ++i) {
    appendVertex(&bytes, map, i, tolerance);
  }
  for (const Eigen::Vector3i& face : faces) {
    appendLittleEndian(&bytes, std::uint8_t{3});
    for (int c = 0; c < 3; ++c) {
      appendLittleEndian(&bytes, static_cast<std::int32_t>(face[c]));
    }
  }
  return writeOutputFile(path, bytes, kWhat);
}

}  // namespace freeform_inspection
