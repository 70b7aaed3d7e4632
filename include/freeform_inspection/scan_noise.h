// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <cstddef>

#include "freeform_inspection/types.h"

/// @file scan_noise.h
/// The scan's own noise, measured without the CAD: it sizes the cloud curvature fit
/// (descriptor.h) and the residual gate of the registration (pipeline.h).

namespace freeform_inspection {

/// @brief The scan's noise along the surface normal [m]: the median over up to `samples`
/// evenly spread points of the RMS residual of a least-squares quadric fitted to the neighbours
/// within `radius` (at least 16), corrected for the quadric's 6 degrees of freedom. A quadric
/// takes up the neighbourhood's curvature, which a plane would count as noise. A neighbourhood
/// no wider than the noise cannot see it, and a ball of a few σ clips the noise's tails: when
/// the estimate exceeds a fifth of the radius, it is measured once more over 6× the estimate.
/// Scans above 50,000 points are measured on an evenly spread subset of that many (the estimate
/// does not depend on the density). Fewer than 32 points: 0.
double estimateScanNoise(const Points& points, double radius, std::size_t samples = 1000);

}  // namespace freeform_inspection
