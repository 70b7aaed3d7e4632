// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "binary_util.h"
#include "checks.h"
#include "ply_header.h"
#include "readers.h"
#include "text_util.h"

// Our own PLY reader instead of PCL's: PCL silently drops double-precision coordinates, and we
// need strict bounds checks against lying headers.

namespace freeform_inspection {
namespace io_internal {
namespace {

enum class ReadResult { kOk, kEnd, kMalformed };

// One scalar at a time from the data section, ascii tokens or binary words.
class ValueReader {
 public:
  ValueReader(std::string_view data, PlyFormat format)
      : data_(data),
        ascii_(format == PlyFormat::kAscii),
        little_endian_(format == PlyFormat::kBinaryLittleEndian) {}

  ReadResult read(PlyType type, double* value) {
    return ascii_ ? readAscii(type, value) : readBinary(type, value);
  }

  bool ascii() const { return ascii_; }
  std::size_t remaining() const { return data_.size() - pos_; }
  std::string_view lastToken() const { return token_; }

 private:
  ReadResult readAscii(PlyType type, double* value) {
    if (!nextToken(data_, &pos_, &token_)) {
      return ReadResult::kEnd;
    }
    if (!parseDouble(token_, value)) {
      return ReadResult::kMalformed;
    }
    if (type == PlyType::kFloat32) {
      *value = toFloatPrecision(*value);  // same value as the binary file would hold
    }
    return ReadResult::kOk;
  }

  static double toFloatPrecision(double value) {
    constexpr double kFloatMax = std::numeric_limits<float>::max();
    if (std::fabs(value) > kFloatMax) {  // float conversion would be undefined
      return value > 0 ? std::numeric_limits<double>::infinity()
                       : -std::numeric_limits<double>::infinity();
    }
    return static_cast<double>(static_cast<float>(value));
  }

  ReadResult readBinary(PlyType type, double* value) {
    const std::size_t size = plyTypeSize(type);
    if (remaining() < size) {
      return ReadResult::kEnd;
    }
    const char* p = data_.data() + pos_;
    pos_ += size;
    switch (type) {
      case PlyType::kInt8:
        *value = loadScalar<std::int8_t>(p, little_endian_);
        break;
      case PlyType::kUint8:
        *value = loadScalar<std::uint8_t>(p, little_endian_);
        break;
      case PlyType::kInt16:
        *value = loadScalar<std::int16_t>(p, little_endian_);
        break;
      case PlyType::kUint16:
        *value = loadScalar<std::uint16_t>(p, little_endian_);
        break;
      case PlyType::kInt32:
        *value = loadScalar<std::int32_t>(p, little_endian_);
        break;
      case PlyType::kUint32:
        *value = loadScalar<std::uint32_t>(p, little_endian_);
        break;
      case PlyType::kFloat32:
        *value = static_cast<double>(loadScalar<float>(p, little_endian_));
        break;
      case PlyType::kFloat64:
        *value = loadScalar<double>(p, little_endian_);
        break;
    }
    return ReadResult::kOk;
  }

  std::string_view data_;
  std::size_t pos_ = 0;
  std::string_view token_;
  bool ascii_;
  bool little_endian_;
};

// Smallest number of bytes one item can occupy: binary sizes, or one character per ascii token.
std::size_t minimumBytes(const ValueReader& reader, PlyType type) {
  return reader.ascii() ? 1 : plyTypeSize(type);
}

std::size_t minimumRecordBytes(const ValueReader& reader, const PlyElement& element) {
  std::size_t bytes = 0;
  for (const PlyProperty& property : element.properties) {
    bytes += minimumBytes(reader, property.is_list ? property.count_type : property.type);
  }
  return bytes;
}

// Where a vertex property goes: 0-2 position, 3-5 normal, -1 ignored.
int vertexSlot(const std::string& name) {
  static const char* const kNames[] = {"x", "y", "z", "nx", "ny", "nz"};
  for (int i = 0; i < 6; ++i) {
    if (name == kNames[i]) {
      return i;
    }
  }
  return -1;
}

bool isFaceIndexList(const PlyElement& element, const PlyProperty& property) {
  return element.name == "face" &&
         (property.name == "vertex_indices" || property.name == "vertex_index");
}

class PlyDataReader {
 public:
  PlyDataReader(const std::string& path, const PlyHeader& header, std::string_view data)
      : path_(path), header_(header), reader_(data, header.format) {}

  Status read(RawGeometry* out) {
    Status status = prepare(out);
    for (std::size_t e = 0; status.ok() && e < header_.elements.size(); ++e) {
      status = readElement(header_.elements[e], out);
    }
    if (!status.ok()) {
      return status;
    }
    if (short_polygons_ > 0) {
      out->warnings.push_back("dropped " + std::to_string(short_polygons_) +
                              " PLY faces with fewer than 3 vertices");
    }
    if (!reader_.ascii() && reader_.remaining() > 0) {
      out->warnings.push_back("ignored " + std::to_string(reader_.remaining()) +
                              " bytes after the last PLY element");
    }
    return Status::success();
  }

 private:
  Status invalid(const std::string& why) const {
    return Status::failure(StatusCode::kInvalidInput, "'" + path_ + "': " + why);
  }

  // Checks the vertex and face declarations before any data is read.
  Status prepare(RawGeometry* out) {
    const auto named = [this](const char* name) {
      return std::count_if(header_.elements.begin(),
                           header_.elements.end(),
                           [name](const PlyElement& e) { return e.name == name; });
    };
    if (named("vertex") != 1 || named("face") > 1) {
      return invalid("expected one 'vertex' element and at most one 'face' element, found " +
                     std::to_string(named("vertex")) + " and " + std::to_string(named("face")));
    }
    for (const PlyElement& element : header_.elements) {
      if (element.name == "vertex") {
        if (element.count > static_cast<std::size_t>(INT_MAX)) {
          return invalid("too many vertices (" + std::to_string(element.count) + ")");
        }
        vertex_count_ = element.count;
        out->file_vertices = element.count;
        int found = 0;
        for (const PlyProperty& property : element.properties) {
          const int slot = vertexSlot(property.name);
          if (slot >= 0 && property.is_list) {
            return invalid("vertex property '" + property.name + "' must not be a list");
          }
          found |= slot >= 0 ? 1 << slot : 0;
        }
        for (int axis = 0; axis < 3; ++axis) {
          if ((found & (1 << axis)) == 0) {
            return invalid(std::string("vertex element has no '") + "xyz"[axis] + "' property");
          }
        }
        has_normals_ = (found & 0x38) == 0x38;
      } else if (element.name == "face") {
        out->file_faces = element.count;
        const bool has_indices = std::any_of(
            element.properties.begin(), element.properties.end(), [&element](const PlyProperty& p) {
              return isFaceIndexList(element, p);
            });
        const bool scalar_indices =
            std::any_of(element.properties.begin(), element.properties.end(), [](const auto& p) {
              return !p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index");
            });
        if (!has_indices || scalar_indices) {
          return invalid("face element has no 'vertex_indices' list property");
        }
      }
    }
    return Status::success();
  }

  Status readElement(const PlyElement& element, RawGeometry* out) {
    const std::size_t record_bytes = minimumRecordBytes(reader_, element);
    if (record_bytes == 0 || element.count == 0) {
      return Status::success();  // nothing stored, nothing to skip
    }
    // A lying count must fail here, before anything is reserved.
    if (element.count > reader_.remaining() / record_bytes) {
      return invalid("element '" + element.name + "' declares " + std::to_string(element.count) +
                     " records of at least " + std::to_string(record_bytes) + " bytes but only " +
                     std::to_string(reader_.remaining()) + " bytes of data remain");
    }
    const bool is_vertex = element.name == "vertex";
    // Each property's vertex slot (x..nz, or none), named once, not for every value.
    std::vector<int> slot_of(element.properties.size(), -1);
    for (std::size_t p = 0; is_vertex && p < slot_of.size(); ++p) {
      slot_of[p] = vertexSlot(element.properties[p].name);
    }
    if (is_vertex && !reader_.ascii()) {
      out->vertices.reserve(element.count);
      if (has_normals_) {
        out->normals.reserve(element.count);
      }
    }
    for (std::size_t record = 0; record < element.count; ++record) {
      double slots[6] = {0, 0, 0, 0, 0, 0};
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        double* slot = slot_of[p] >= 0 ? &slots[slot_of[p]] : nullptr;
        Status status = property.is_list ? readList(element, property, record, out)
                                         : readScalar(element, property, record, slot);
        if (!status.ok()) {
          return status;
        }
      }
      if (is_vertex) {
        out->vertices.emplace_back(slots[0], slots[1], slots[2]);
        if (has_normals_) {
          out->normals.emplace_back(slots[3], slots[4], slots[5]);
        }
      }
    }
    return Status::success();
  }

  Status readValue(PlyType type, const PlyElement& element, std::size_t record, double* value) {
    switch (reader_.read(type, value)) {
      case ReadResult::kOk:
        return Status::success();
      case ReadResult::kEnd:
        return invalid("data ends in element '" + element.name + "' record " +
                       std::to_string(record) + " of " + std::to_string(element.count) +
                       " (truncated file?)");
      case ReadResult::kMalformed:
        break;
    }
    return invalid("bad number '" + std::string(reader_.lastToken()) + "' in element '" +
                   element.name + "' record " + std::to_string(record));
  }

  // Reads one value into `slot` (nowhere when null: a property the geometry does not use).
  Status readScalar(const PlyElement& element,
                    const PlyProperty& property,
                    std::size_t record,
                    double* slot) {
    double value = 0.0;
    Status status = readValue(property.type, element, record, &value);
    if (status.ok() && slot != nullptr) {
      *slot = value;
    }
    return status;
  }

  Status readList(const PlyElement& element,
                  const PlyProperty& property,
                  std::size_t record,
                  RawGeometry* out) {
    double count_value = 0.0;
    Status status = readValue(property.count_type, element, record, &count_value);
    if (!status.ok()) {
      return status;
    }
    const auto where = [&] {
      return " in element '" + element.name + "' record " + std::to_string(record);
    };
    if (count_value < 0.0) {
      return invalid("negative list count " + valueText(count_value) + where());
    }
    if (std::floor(count_value) != count_value) {
      return invalid("non-integer list count " + valueText(count_value) + where());
    }
    const std::size_t item_bytes = minimumBytes(reader_, property.type);
    if (count_value > static_cast<double>(reader_.remaining() / item_bytes)) {
      return invalid("list count " + valueText(count_value) + where() + " needs at least " +
                     formatNumber(count_value * static_cast<double>(item_bytes)) +
                     " bytes but only " + std::to_string(reader_.remaining()) +
                     " remain (truncated file?)");
    }
    const auto count = static_cast<std::size_t>(count_value);
    const bool is_face = isFaceIndexList(element, property);
    polygon_.clear();
    for (std::size_t i = 0; i < count; ++i) {
      double value = 0.0;
      status = readValue(property.type, element, record, &value);
      if (!status.ok()) {
        return status;
      }
      if (is_face) {
        if (!(value >= 0.0 && value < static_cast<double>(vertex_count_)) ||
            std::floor(value) != value) {
          return invalid("face " + std::to_string(record) + " references vertex " +
                         valueText(value) + " but the file has " + std::to_string(vertex_count_) +
                         " vertices");
        }
        polygon_.push_back(static_cast<int>(value));
      }
    }
    if (is_face) {
      addFan(out);
    }
    return Status::success();
  }

  // The value just read as the file spells it (ascii) or as a number (binary).
  std::string valueText(double value) const {
    if (reader_.ascii()) {
      return std::string(reader_.lastToken());
    }
    if (std::floor(value) == value && std::fabs(value) < 1e18) {
      return std::to_string(static_cast<long long>(value));
    }
    return std::to_string(value);
  }

  // Polygons become triangle fans around their first corner.
  void addFan(RawGeometry* out) {
    if (polygon_.size() < 3) {
      ++short_polygons_;
      return;
    }
    for (std::size_t i = 1; i + 1 < polygon_.size(); ++i) {
      out->faces.emplace_back(polygon_[0], polygon_[i], polygon_[i + 1]);
    }
  }

  const std::string& path_;
  const PlyHeader& header_;
  ValueReader reader_;
  std::size_t vertex_count_ = 0;
  bool has_normals_ = false;
  std::size_t short_polygons_ = 0;
  std::vector<int> polygon_;
};

}  // namespace

Status readPly(const std::string& path, std::string_view bytes, RawGeometry* out) {
  PlyHeader header;
  Status status = parsePlyHeader(path, bytes, &header);
  if (!status.ok()) {
    return status;
  }
  PlyDataReader reader(path, header, bytes.substr(header.data_offset));
  return reader.read(out);
}

}  // namespace io_internal
}  // namespace freeform_inspection
