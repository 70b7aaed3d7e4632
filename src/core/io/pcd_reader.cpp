// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <cstdint>
#include <exception>
#include <string>

#include "binary_util.h"
#include "pcd_header.h"
#include "readers.h"
#include <pcl/PCLPointCloud2.h>
#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>

// PCL headers are slow to compile and PCL's io pulls VTK and OpenNI (about 70 shared libraries,
// 40 ms at every process start): this file is the only one that includes them, and it is built
// as a module loaded on the first PCD read (pcd_module.cpp), not into the core library. It uses
// nothing of the core library but header-only code, so a static core is not linked into it twice.

namespace freeform_inspection {
namespace io_internal {
namespace {

using Field = pcl::PCLPointField;

// Reads float or double fields by name, so clouds of any point type (XYZ, XYZI, XYZRGBNormal,
// double-precision survey data) load without a matching PCL point struct.
class FieldExtractor {
 public:
  FieldExtractor(const std::string& path, const pcl::PCLPointCloud2& cloud)
      : path_(path), cloud_(cloud) {}

  // Finds `name` and checks that it is a float or double inside the point record.
  Status find(const std::string& name, const Field** field) const {
    *field = nullptr;
    for (const Field& candidate : cloud_.fields) {
      if (candidate.name == name) {
        *field = &candidate;
      }
    }
    if (*field == nullptr) {
      return invalid("has no '" + name + "' field");
    }
    const Field& f = **field;
    if (f.datatype != Field::FLOAT32 && f.datatype != Field::FLOAT64) {
      return invalid("field '" + name + "' has PCL datatype " + std::to_string(f.datatype) +
                     "; expected FLOAT32 (7) or FLOAT64 (8)");
    }
    if (f.offset + valueSize(f) > cloud_.point_step) {
      return invalid("field '" + name + "' lies outside the " + std::to_string(cloud_.point_step) +
                     "-byte point");
    }
    return Status::success();
  }

  double value(const Field& field, std::size_t row, std::size_t column) const {
    const char* p = reinterpret_cast<const char*>(cloud_.data.data()) + row * cloud_.row_step +
                    column * cloud_.point_step + field.offset;
    const bool little_endian = cloud_.is_bigendian == 0;
    return field.datatype == Field::FLOAT32
               ? static_cast<double>(loadScalar<float>(p, little_endian))
               : loadScalar<double>(p, little_endian);
  }

  Status invalid(const std::string& why) const {
    return Status::failure(StatusCode::kInvalidInput, "PCD '" + path_ + "' " + why);
  }

 private:
  static std::size_t valueSize(const Field& field) {
    return field.datatype == Field::FLOAT32 ? 4 : 8;
  }

  const std::string& path_;
  const pcl::PCLPointCloud2& cloud_;
};

// Copies x/y/z (and normals) into `out`; with a null `out` only checks that the fields exist.
Status extract(const std::string& path, const pcl::PCLPointCloud2& cloud, RawGeometry* out) {
  const FieldExtractor extractor(path, cloud);
  const Field* xyz[3] = {nullptr, nullptr, nullptr};
  for (int axis = 0; axis < 3; ++axis) {
    Status status = extractor.find(std::string(1, "xyz"[axis]), &xyz[axis]);
    if (!status.ok()) {
      return status;
    }
  }
  const Field* normal[3] = {nullptr, nullptr, nullptr};
  bool has_normals = true;
  for (int axis = 0; axis < 3; ++axis) {
    has_normals =
        has_normals && extractor.find(std::string("normal_") + "xyz"[axis], &normal[axis]).ok();
  }
  if (out == nullptr) {
    return Status::success();  // fields checked only
  }
  const std::size_t width = cloud.width;
  const std::size_t height = cloud.height;
  // Never trust the header against the buffer PCL actually filled.
  if (cloud.row_step < width * cloud.point_step || cloud.data.size() < height * cloud.row_step) {
    return extractor.invalid("declares " + std::to_string(width) + "x" + std::to_string(height) +
                             " points but holds only " + std::to_string(cloud.data.size()) +
                             " bytes");
  }
  out->file_vertices = width * height;
  if (height > 1) {
    out->width = width;
    out->height = height;
  }
  out->vertices.reserve(out->file_vertices);
  if (has_normals) {
    out->normals.reserve(out->file_vertices);
  }
  for (std::size_t row = 0; row < height; ++row) {
    for (std::size_t column = 0; column < width; ++column) {
      out->vertices.emplace_back(extractor.value(*xyz[0], row, column),
                                 extractor.value(*xyz[1], row, column),
                                 extractor.value(*xyz[2], row, column));
      if (has_normals) {
        out->normals.emplace_back(extractor.value(*normal[0], row, column),
                                  extractor.value(*normal[1], row, column),
                                  extractor.value(*normal[2], row, column));
      }
    }
  }
  return Status::success();
}

// PCL's own view of the header must be the one parsePcdHeader checked, fields one after the other
// and the buffer holding every point: its ascii reader writes past the buffer otherwise (found by
// fuzz_pcd under valgrind; PCL is not instrumented, ASan cannot see its writes).
Status checkHeaderLayout(const std::string& path,
                         const PcdHeader& header,
                         const pcl::PCLPointCloud2& cloud,
                         unsigned int data_index) {
  std::uint64_t step = 0;
  for (const Field& field : cloud.fields) {
    if (field.offset != step) {
      break;
    }
    step += std::uint64_t{field.count} * pcl::getFieldSize(field.datatype);
  }
  const std::uint64_t points = std::uint64_t{cloud.width} * cloud.height;
  if (step != cloud.point_step || step != header.point_bytes || points != header.points ||
      data_index != header.data_offset || cloud.data.size() != points * step) {
    return Status::failure(StatusCode::kInvalidInput,
                           "PCD '" + path + "': PCL reads the header as " + std::to_string(points) +
                               " points of " + std::to_string(cloud.point_step) + " bytes, not " +
                               std::to_string(header.points) + " of " +
                               std::to_string(header.point_bytes));
  }
  return Status::success();
}

}  // namespace

Status readPcdWithPcl(const std::string& path, const PcdHeader& header, RawGeometry* out) {
  const auto cannot_read = [&path](const std::string& why) {
    return Status::failure(StatusCode::kInvalidInput, "cannot read PCD '" + path + "': " + why);
  };
  Status status;
  pcl::PCLPointCloud2 cloud;
  Eigen::Vector4f origin;  // PCL leaves parts unset on a malformed VIEWPOINT: not used
  Eigen::Quaternionf orientation;
  int version = 0;
  try {
    pcl::PCDReader reader;
    // The header first: PCL 1.13 crashes in read() on a header without fields (PCL #5854).
    int data_type = 0;
    unsigned int data_index = 0;
    if (reader.readHeader(path, cloud, origin, orientation, version, data_type, data_index) < 0) {
      return cannot_read("malformed header");
    }
    if (cloud.fields.empty()) {
      return cannot_read("header declares no FIELDS");
    }
    status = extract(path, cloud, nullptr);  // names a missing or mistyped x/y/z
    if (!status.ok() || std::size_t{cloud.width} * cloud.height == 0) {
      return status;
    }
    status = checkHeaderLayout(path, header, cloud, data_index);
    if (!status.ok()) {
      return status;
    }
    if (reader.read(path, cloud, origin, orientation, version) < 0) {
      return cannot_read("malformed header or data");
    }
  } catch (const std::exception& e) {
    return cannot_read(e.what());
  }
  return extract(path, cloud, out);
}

}  // namespace io_internal
}  // namespace freeform_inspection

// The module's one entry point, looked up by name (pcd_module.cpp).
extern "C" void freeform_inspection_read_pcd(
    const std::string* path,
    const freeform_inspection::io_internal::PcdHeader* header,
    freeform_inspection::io_internal::RawGeometry* out,
    freeform_inspection::Status* status) {
  *status = freeform_inspection::io_internal::readPcdWithPcl(*path, *header, out);
}
