// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>

#include "freeform_inspection/types.h"

/// @file surface_sampling.h
/// Uniform random points on a mesh surface: synthetic scans for tests, benchmarks and the case
/// generator.

namespace freeform_inspection {

/// Points with the outward normal of the face each was drawn from.
struct SurfaceSample {
  Points points;   ///< [m]
  Points normals;  ///< unit face normals
};

/// @brief `count` points uniform by area (faces chosen in proportion to their area, then a
/// uniform barycentric point), deterministic for a seed; optional Gaussian noise of standard
/// deviation `noise_sigma` [m] along the face normal.
SurfaceSample sampleSurface(const TriangleMesh& mesh,
                            std::size_t count,
                            unsigned seed,
                            double noise_sigma = 0.0);

}  // namespace freeform_inspection
