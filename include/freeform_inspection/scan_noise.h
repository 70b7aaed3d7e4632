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
/// in a ball (at least 16), corrected for the quadric's 6 degrees of freedom. A quadric takes
/// up the ball's curvature, which a plane would count as noise. A ball no wider than the noise
/// cannot see it (and clips its tails), so while the estimate exceeds a fifth of the radius the
/// ball grows to 6× the estimate and the measurement is repeated. Two starts, the smaller
/// estimate kept: a small ball (the median distance to the 32nd neighbour, at most `radius`)
/// widened up to 3 times, which stays on one wall of a thin part; and a ball of `radius`
/// widened once, which does not run away into the opposite wall of a walled part at high noise.
/// Scans above 50,000 points are measured on an evenly spread subset of that many (the estimate
/// does not depend on the density). Fewer than 32 points or no radius: 0.
double estimateScanNoise(const Points& points, double radius, std::size_t samples = 1000);

}  // namespace freeform_inspection
