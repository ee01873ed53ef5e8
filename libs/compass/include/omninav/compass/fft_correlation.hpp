#pragma once
// The whole distance function d(I_i, I_j, α), α = 0..W−1, in O(H·W·log W) by masked circular
// cross-correlation with FFTW: what lets the compass run at 3 pixels per degree (000 §3.4.1
// found it the most accurate resolution and could not afford it). fft_correlation.cpp derives
// it; minimiser (c) rounds these values to the exact integer costs they approximate.

#include <vector>

#include "omninav/compass/distance.hpp"
#include "omninav/compass/minimiser.hpp"

namespace omninav::compass {

// d²(α) for every shift α in [0, W), as the FFT computes them (floating point, before
// rounding), for the L2 metric. The frames' transforms are cached in the frames. Throws
// UsageError for the L1 metric and InputError for frames of different shapes.
std::vector<double> correlation_costs(const DistanceFunction& distance, const CompassFrame& first,
                                      const CompassFrame& second,
                                      FftPlanning planning = FftPlanning::kEstimate);

}  // namespace omninav::compass
