#pragma once
// The turn between two views from their cross-power P_k = Σ_lines F'_k·conj(F_k) (001 Eq. 1 over
// several components), before it is polished on the correlation: k = 1 gives it without
// ambiguity, then each k = 2..m−1 refines it on the branch of its arg(P_k)/k nearest the running
// estimate, weighted by k·|P_k|. Shared by relative_heading() and its test oracle
// (tests/signature/direct_phase_heading.hpp), which differ in how they compute P_k and the
// correlation, not in this.

#include <cmath>
#include <complex>

#include "omninav/core/angles.hpp"

namespace omninav::signature::detail {

// `cross_at(k)` returns P_k as a std::complex<double>, for k = 1..m−1.
template <typename CrossAt>
double turn_from_branches(const CrossAt& cross_at, int m) {
  // 1. Coarse, from k = 1.
  const std::complex<double> first = cross_at(1);
  double turn = -std::arg(first);
  double weight_sum = std::abs(first);
  double weighted = turn * weight_sum;
  // 2. Refined with k = 2..m−1, each on the branch nearest the running estimate.
  for (int k = 2; k < m; ++k) {
    const std::complex<double> p = cross_at(k);
    const double magnitude = std::abs(p);
    if (magnitude <= 0.0) continue;
    const double kk = static_cast<double>(k);
    const double base = -std::arg(p) / kk;
    const double period = kTwoPi / kk;
    const double running = weight_sum > 0.0 ? weighted / weight_sum : turn;
    const double candidate = base + period * std::round((running - base) / period);
    const double weight = kk * magnitude;
    weighted += weight * candidate;
    weight_sum += weight;
  }
  return weight_sum > 0.0 ? weighted / weight_sum : turn;
}

}  // namespace omninav::signature::detail
