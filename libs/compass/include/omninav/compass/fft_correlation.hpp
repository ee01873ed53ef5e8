#pragma once
// The whole distance function d(I_i, I_j, α), α = 0..W−1, in O(H·W·log W) by masked circular
// cross-correlation with FFTW: what lets the compass run at 3 pixels per degree (Labrosse 2006,
// §3.4.1 found it the most accurate resolution and could not afford it). fft_correlation.cpp
// derives it and bounds its error; minimiser (c) evaluates exactly the shifts that may be the
// minimum.

#include <vector>

#include "omninav/compass/distance.hpp"
#include "omninav/compass/minimiser.hpp"

namespace omninav::compass {

struct CorrelationCosts {
  std::vector<double> costs;  // the estimate of d²(α) for every shift α in [0, W)
  double error_bound = 0.0;  // |costs[α] − d²(α)| ≤ error_bound at every α (the exact cost)
};

// d²(α) for every shift, for the L2 metric, as the FFT estimates them (single-precision
// transforms), with the bound on their error. The frames' transforms are cached in the frames.
// Throws UsageError for the L1 metric and InputError for frames of different shapes.
CorrelationCosts correlation_costs(const DistanceFunction& distance, const CompassFrame& first,
                                   const CompassFrame& second,
                                   FftPlanning planning = FftPlanning::kEstimate);

}  // namespace omninav::compass
