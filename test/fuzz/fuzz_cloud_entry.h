// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>
#include <cstdint>

#include "fuzz_outcome.h"
#include <sensor_msgs/PointCloud2.h>

/// @file fuzz_cloud_entry.h
/// The PointCloud2 fuzz entry: fuzz bytes decoded into a message for cloudToScan(). Shared by the
/// fuzz_cloud target and the ROS corpus test (test/unit/fuzz_cloud_corpus_test.cpp).

namespace freeform_inspection {
namespace fuzz {

/// @brief Decodes fuzz bytes into a PointCloud2 (missing bytes read as 0):
/// - 1 flags byte: bit 0 is_bigendian, bit 1 is_dense, bits 2-3 how row_step is made;
/// - width, height, point_step as "sizes": one byte b, the value b when b < 0x80, else the next
///   4 bytes little-endian (small values keep the layout near-consistent, any value stays
///   reachable);
/// - row_step: width · point_step (mode 0, cut to 32 bits like a careless sender), that plus one
///   byte (mode 1), else a size;
/// - 1 byte field count (mod 9); per field: a name byte (x, y, z, rgb, intensity, normal_x, the
///   empty name, or raw bytes of length (next byte mod 8)), an offset size, a datatype byte and a
///   count size;
/// - the rest of the bytes: data.
sensor_msgs::PointCloud2 decodeCloud(const std::uint8_t* data, std::size_t size);

/// cloudToScan() on decodeCloud(): a failure has a message and no points; a success has
/// width · height points and the grid only when height > 1.
EntryOutcome fuzzCloud(const std::uint8_t* data, std::size_t size);

}  // namespace fuzz
}  // namespace freeform_inspection
