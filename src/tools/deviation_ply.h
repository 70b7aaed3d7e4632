// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>

#include "freeform_inspection/deviation.h"
#include "freeform_inspection/types.h"

namespace freeform_inspection {

/// @brief Writes a deviation map as binary little-endian PLY (docs/reports.md): per vertex
/// x y z (float, CAD frame, metres), deviation (float [m], NaN unmatched), in_tolerance (uchar
/// 0/1), defect (int, -1 none), shape_deviation (float, NaN unknown) and red green blue (uchar,
/// the colour scale of deviation_colours.h); a face element with `vertex_indices` when `faces`
/// is non-empty.
/// @param map one entry per point; `shape_deviation` and `defect` may be empty (written as NaN
/// and -1).
/// @param faces triangles indexing `map.points`, or empty for a cloud.
/// @param tolerance each point's band (regions.h's toleranceBands()), or the part's.
/// @return kInvalidInput naming the file for inconsistent sizes, a face index out of range or
/// an I/O failure (with the OS reason).
Status saveDeviationPly(const std::string& path,
                        const DeviationMap& map,
                        const Triangles& faces,
                        const ToleranceBands& tolerance);

}  // namespace freeform_inspection
