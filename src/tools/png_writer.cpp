// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// A minimal PNG encoder on zlib: PNG is a signature plus CRC-framed chunks around one zlib
// stream, so compress() and crc32() are all it needs (libpng would add a dependency and a
// setjmp-based error API for no gain here).
#include "png_writer.h"

#include <cstdint>
#include <vector>

#include <zlib.h>

namespace freeform_inspection {
namespace {

void appendBigEndian32(std::string* out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) {
    out->push_back(static_cast<char>((value >> shift) & 0xffu));
  }
}

// One chunk: length, type, data, CRC-32 over type and data.
void appendChunk(std::string* out, const char* type, const std::string& data) {
  appendBigEndian32(out, static_cast<std::uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  out->append(body);
  const auto* bytes = reinterpret_cast<const Bytef*>(body.data());
  appendBigEndian32(out,
                    static_cast<std::uint32_t>(
                        crc32(crc32(0L, Z_NULL, 0), bytes, static_cast<uInt>(body.size()))));
}

std::string headerChunk(const RgbImage& image) {
  std::string data;
  appendBigEndian32(&data, static_cast<std::uint32_t>(image.width));
  appendBigEndian32(&data, static_cast<std::uint32_t>(image.height));
  data.push_back(8);  // bits per channel
  data.push_back(2);  // colour type: truecolour RGB
  data.push_back(0);  // compression: deflate
  data.push_back(0);  // filter method: adaptive (each row starts with its filter type)
  data.push_back(0);  // no interlace
  return data;
}

// Rows with filter type 0 (none): the renderer's flat colours and white background deflate
// well without prediction.
std::vector<Bytef> filteredRows(const RgbImage& image) {
  const std::size_t row_bytes = static_cast<std::size_t>(image.width) * 3;
  std::vector<Bytef> rows;
  rows.reserve((row_bytes + 1) * static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    rows.push_back(0);
    const auto begin =
        image.pixels.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * row_bytes);
    rows.insert(rows.end(), begin, begin + static_cast<std::ptrdiff_t>(row_bytes));
  }
  return rows;
}

}  // namespace

std::string encodePng(const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() !=
          static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3) {
    return "";
  }
  const std::vector<Bytef> rows = filteredRows(image);
  uLongf packed_size = compressBound(static_cast<uLong>(rows.size()));
  std::string packed(packed_size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(packed.data()),
                &packed_size,
                rows.data(),
                static_cast<uLong>(rows.size()),
                Z_BEST_COMPRESSION) != Z_OK) {
    return "";
  }
  packed.resize(packed_size);
  std::string png = "\x89PNG\r\n\x1a\n";
  appendChunk(&png, "IHDR", headerChunk(image));
  appendChunk(&png, "IDAT", packed);
  appendChunk(&png, "IEND", "");
  return png;
}

}  // namespace freeform_inspection
