// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <sensor_msgs/PointCloud2.h>

#include "freeform_inspection/types.h"

/// @file cloud_conversion.h
/// PointCloud2 → Scan. Apart from the rest of conversions.h (which includes it) because it needs
/// no generated message of this package: the PointCloud2 fuzz target (test/fuzz/) builds it alone.

namespace freeform_inspection_ros {

namespace fi = freeform_inspection;

/// A PointCloud2 read into a scan, or the reason it could not be read.
struct CloudConversion {
  fi::Status status;  ///< kInvalidInput for inconsistent sizes or missing/odd x, y, z fields
  fi::Scan scan;      ///< every point as stored, NaN included (the pipeline removes and counts)
};

/// @brief Reads x, y, z by field name (FLOAT32 or FLOAT64), organized or not, after checking that
/// width, height, point_step, row_step and the data size agree. x, y and z must each appear once
/// (a duplicated coordinate field is refused). Other fields are ignored.
CloudConversion cloudToScan(const sensor_msgs::PointCloud2& cloud);

}  // namespace freeform_inspection_ros
