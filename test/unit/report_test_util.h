// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>
#include <zlib.h>

/// Independent readers for the report outputs (base64, PNG), sharing no code with the writers,
/// for report_output_test and cli_test.
namespace freeform_inspection::report_test {

/// Decodes standard base64; stops at the first character outside the alphabet or at '='.
inline std::string base64Decode(std::string_view text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string bytes;
  std::uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    const auto digit = alphabet.find(c);
    if (digit == std::string::npos) {
      break;
    }
    bits = (bits << 6) | static_cast<std::uint32_t>(digit);
    count += 6;
    if (count >= 8) {
      count -= 8;
      bytes.push_back(static_cast<char>((bits >> count) & 0xffu));
    }
  }
  return bytes;
}

/// The payloads of every `data:<mime>;base64,` URI in `html`, decoded.
inline std::vector<std::string> dataUris(const std::string& html, const std::string& mime) {
  const std::string prefix = "data:" + mime + ";base64,";
  std::vector<std::string> payloads;
  for (auto at = html.find(prefix); at != std::string::npos; at = html.find(prefix, at + 1)) {
    const auto begin = at + prefix.size();
    payloads.push_back(
        base64Decode(std::string_view(html).substr(begin, html.find('"', begin) - begin)));
  }
  return payloads;
}

/// What a PNG file says about itself, after checking its chunks.
struct PngInfo {
  std::string error;  ///< empty when the file is a valid 8-bit RGB PNG
  int width = 0;
  int height = 0;
  std::string rows;  ///< inflated image data: per row a filter byte then 3 bytes per pixel
};

inline std::uint32_t bigEndian32(std::string_view bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    value = (value << 8) | static_cast<unsigned char>(bytes[at + i]);
  }
  return value;
}

/// Walks the chunks (lengths, CRCs), reads IHDR and inflates the IDAT data.
inline PngInfo readPng(std::string_view png) {
  PngInfo info;
  if (png.substr(0, 8) != std::string_view("\x89PNG\r\n\x1a\n", 8)) {
    info.error = "no PNG signature";
    return info;
  }
  std::string idat;
  std::size_t at = 8;
  bool ended = false;
  while (!ended && at + 12 <= png.size()) {
    const std::uint32_t length = bigEndian32(png, at);
    if (at + 12 + length > png.size()) {
      info.error = "truncated chunk";
      return info;
    }
    const std::string_view type = png.substr(at + 4, 4);
    const std::string_view data = png.substr(at + 8, length);
    const auto crc = crc32(0L, reinterpret_cast<const Bytef*>(png.data() + at + 4), length + 4);
    if (crc != bigEndian32(png, at + 8 + length)) {
      info.error = "bad CRC in " + std::string(type);
      return info;
    }
    if (type == "IHDR") {
      info.width = static_cast<int>(bigEndian32(data, 0));
      info.height = static_cast<int>(bigEndian32(data, 4));
      if (data[8] != 8 || data[9] != 2) {
        info.error = "not 8-bit RGB";
      }
    } else if (type == "IDAT") {
      idat.append(data);
    }
    ended = type == "IEND";
    at += 12 + length;
  }
  if (!ended) {
    info.error = "no IEND";
    return info;
  }
  uLongf size = static_cast<uLongf>(info.height) * (1 + 3 * static_cast<uLongf>(info.width));
  info.rows.resize(size);
  if (uncompress(reinterpret_cast<Bytef*>(info.rows.data()),
                 &size,
                 reinterpret_cast<const Bytef*>(idat.data()),
                 idat.size()) != Z_OK ||
      size != info.rows.size()) {
    info.error = "image data does not inflate to height x (1 + 3 width) bytes";
  }
  return info;
}

/// One vertex of a deviation PLY (docs/reports.md).
struct DeviationVertex {
  float x = 0, y = 0, z = 0, deviation = 0, shape_deviation = 0;
  int in_tolerance = 0;
  int defect = -1;
  int region = -1;
  unsigned char rgb[3] = {0, 0, 0};
};

/// The vertices of a deviation PLY in the documented binary layout (32 bytes per vertex, right
/// after the header); empty when the header is not the documented one.
inline std::vector<DeviationVertex> readDeviationVertices(const std::string& bytes) {
  const std::string properties =
      "property float x\nproperty float y\nproperty float z\nproperty float deviation\n"
      "property uchar in_tolerance\nproperty int defect\nproperty int region\n"
      "property float shape_deviation\nproperty uchar red\nproperty uchar green\nproperty uchar "
      "blue\n";
  const auto end = bytes.find("end_header\n");
  const auto count_at = bytes.find("element vertex ");
  if (end == std::string::npos || count_at == std::string::npos ||
      bytes.find(properties) == std::string::npos) {
    return {};
  }
  const std::size_t count = std::stoul(bytes.substr(count_at + 15));
  const std::size_t body = end + 11;
  std::vector<DeviationVertex> vertices(count);
  const auto load = [&](std::size_t at, auto* value) {
    std::memcpy(value, bytes.data() + at, sizeof(*value));  // little-endian test hosts
  };
  for (std::size_t i = 0; i < count && body + 32 * (i + 1) <= bytes.size(); ++i) {
    const std::size_t at = body + 32 * i;
    DeviationVertex& v = vertices[i];
    load(at, &v.x);
    load(at + 4, &v.y);
    load(at + 8, &v.z);
    load(at + 12, &v.deviation);
    v.in_tolerance = static_cast<unsigned char>(bytes[at + 16]);
    load(at + 17, &v.defect);
    load(at + 21, &v.region);
    load(at + 25, &v.shape_deviation);
    std::memcpy(v.rgb, bytes.data() + at + 29, 3);
  }
  return vertices;
}

/// RFC 4180 records of a CSV text: fields split at commas outside quotes, "" inside quotes.
inline std::vector<std::vector<std::string>> parseCsv(const std::string& text) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string value;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        value += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        value += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      record.push_back(value);
      value.clear();
    } else if (c == '\n') {
      record.push_back(value);
      records.push_back(record);
      record.clear();
      value.clear();
    } else {
      value += c;
    }
  }
  return records;
}

/// The rows of a CSV text with a header line as {column name: value}; fails the test on a row
/// whose length is not the header's.
inline std::vector<std::map<std::string, std::string>> csvRows(const std::string& text) {
  const auto records = parseCsv(text);
  EXPECT_FALSE(records.empty()) << "no header";
  std::vector<std::map<std::string, std::string>> rows;
  for (std::size_t r = 1; r < records.size(); ++r) {
    EXPECT_EQ(records[r].size(), records[0].size()) << "row " << r;
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < records[0].size() && c < records[r].size(); ++c) {
      row[records[0][c]] = records[r][c];
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace freeform_inspection::report_test
