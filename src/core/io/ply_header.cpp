// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "ply_header.h"

#include <array>
#include <utility>

#include "text_util.h"

namespace freeform_inspection {
namespace io_internal {
namespace {

struct TypeName {
  const char* name;
  PlyType type;
};

// The original names and the sized aliases introduced by later writers (VTK, Open3D, ...).
constexpr std::array<TypeName, 16> kTypeNames = {{{"char", PlyType::kInt8},
                                                  {"int8", PlyType::kInt8},
                                                  {"uchar", PlyType::kUint8},
                                                  {"uint8", PlyType::kUint8},
                                                  {"short", PlyType::kInt16},
                                                  {"int16", PlyType::kInt16},
                                                  {"ushort", PlyType::kUint16},
                                                  {"uint16", PlyType::kUint16},
                                                  {"int", PlyType::kInt32},
                                                  {"int32", PlyType::kInt32},
                                                  {"uint", PlyType::kUint32},
                                                  {"uint32", PlyType::kUint32},
                                                  {"float", PlyType::kFloat32},
                                                  {"float32", PlyType::kFloat32},
                                                  {"double", PlyType::kFloat64},
                                                  {"float64", PlyType::kFloat64}}};

bool parseType(std::string_view name, PlyType* type) {
  for (const TypeName& entry : kTypeNames) {
    if (name == entry.name) {
      *type = entry.type;
      return true;
    }
  }
  return false;
}

Status parseProperty(const std::vector<std::string_view>& w,
                     const std::string& where,
                     PlyProperty* property) {
  const auto bad = [&where](const std::string& why) {
    return Status::failure(StatusCode::kInvalidInput, where + ": " + why);
  };
  if (w.size() == 5 && w[1] == "list") {
    property->is_list = true;
    if (!parseType(w[2], &property->count_type)) {
      return bad("unknown PLY type '" + std::string(w[2]) + "'");
    }
    if (property->count_type == PlyType::kFloat32 || property->count_type == PlyType::kFloat64) {
      return bad("list count type must be an integer, got '" + std::string(w[2]) + "'");
    }
    if (!parseType(w[3], &property->type)) {
      return bad("unknown PLY type '" + std::string(w[3]) + "'");
    }
    property->name = std::string(w[4]);
    return Status::success();
  }
  if (w.size() != 3) {
    return bad("expected 'property <type> <name>' or 'property list <type> <type> <name>'");
  }
  if (!parseType(w[1], &property->type)) {
    return bad("unknown PLY type '" + std::string(w[1]) + "'");
  }
  property->name = std::string(w[2]);
  return Status::success();
}

}  // namespace

std::size_t plyTypeSize(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

Status parsePlyHeader(const std::string& path, std::string_view bytes, PlyHeader* header) {
  LineReader lines(bytes);
  std::string_view line;
  if (!lines.next(&line) || words(line) != std::vector<std::string_view>{"ply"}) {
    return Status::failure(StatusCode::kInvalidInput,
                           "'" + path + "' is not a PLY file (first line is not 'ply')");
  }
  bool have_format = false;
  while (lines.next(&line)) {
    const std::string where =
        "'" + path + "' PLY header line " + std::to_string(lines.lineNumber());
    const auto bad = [&where](const std::string& why) {
      return Status::failure(StatusCode::kInvalidInput, where + ": " + why);
    };
    const std::vector<std::string_view> w = words(line);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") {
      continue;
    }
    if (w[0] == "end_header") {
      if (!have_format) {
        return bad("no 'format' line before end_header");
      }
      header->data_offset = lines.offset();
      return Status::success();
    }
    if (w[0] == "format") {
      if (w.size() != 3) {
        return bad("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
      }
      if (w[1] == "ascii") {
        header->format = PlyFormat::kAscii;
      } else if (w[1] == "binary_little_endian") {
        header->format = PlyFormat::kBinaryLittleEndian;
      } else if (w[1] == "binary_big_endian") {
        header->format = PlyFormat::kBinaryBigEndian;
      } else {
        return bad("unknown PLY format '" + std::string(w[1]) + "'");
      }
      if (w[2] != "1.0") {
        return bad("unsupported PLY version '" + std::string(w[2]) + "'");
      }
      have_format = true;
    } else if (w[0] == "element") {
      long long count = 0;
      if (w.size() != 3 || !parseInteger(w[2], &count) || count < 0) {
        return bad("expected 'element <name> <count>' with a count >= 0, got '" +
                   std::string(line) + "'");
      }
      header->elements.push_back(
          PlyElement{std::string(w[1]), static_cast<std::size_t>(count), {}});
    } else if (w[0] == "property") {
      if (header->elements.empty()) {
        return bad("property before any element");
      }
      PlyProperty property;
      Status status = parseProperty(w, where, &property);
      if (!status.ok()) {
        return status;
      }
      header->elements.back().properties.push_back(std::move(property));
    } else {
      return bad("unexpected '" + std::string(w[0]) + "'");
    }
  }
  return Status::failure(StatusCode::kInvalidInput,
                         "'" + path + "': PLY header has no end_header line");
}

}  // namespace io_internal
}  // namespace freeform_inspection
