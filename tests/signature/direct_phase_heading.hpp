#pragma once
// The oracle for relative_heading() (libs/signature/src/phase_heading.cpp), sharing none of its
// code: the definition of phase_heading.hpp computed the plain way. The cross-power
// P_k = Σ_lines F'_k·conj(F_k) from std::complex coefficients, the low-pass circular correlation
// C(δ) = Σ_k Re(P_k e^{ikδ}) with one std::polar per term, and its global maximum found without
// the phases' branches: C on a grid of 16·m turns (the finest component has period 2π/(m−1),
// so its peaks are 16 samples wide), then every grid peak that could hold the maximum solved for
// C'(δ) = 0 by bisection. The fast path starts from the branches of arg(P_k)/k instead and
// moves to another peak only when its guard's coarser grid sees it higher by 1e-6·Σ|F||F'|
// (phase_heading_test.cpp says what that allows). Used by tests/signature/phase_heading_test.cpp
// and tests/bench/signature_bench.cpp only.

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "omninav/signature/phase_heading.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::signature::testing {
namespace direct {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;

// C(δ) and C'(δ) = −Σ_k k·Im(P_k e^{ikδ}).
inline double correlation(const std::vector<Complex>& cross, double turn) {
  double value = 0.0;
  for (std::size_t k = 1; k < cross.size(); ++k) {
    value += (cross[k] * std::polar(1.0, static_cast<double>(k) * turn)).real();
  }
  return value;
}

inline double slope(const std::vector<Complex>& cross, double turn) {
  double value = 0.0;
  for (std::size_t k = 1; k < cross.size(); ++k) {
    const double kk = static_cast<double>(k);
    value -= kk * (cross[k] * std::polar(1.0, kk * turn)).imag();
  }
  return value;
}

// The maximum of C in [a, b] where C' goes from + to −, by bisection to the last bit.
inline double peak_in(const std::vector<Complex>& cross, double a, double b) {
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double middle = 0.5 * (a + b);
    if (middle <= a || middle >= b) break;
    (slope(cross, middle) > 0.0 ? a : b) = middle;
  }
  return 0.5 * (a + b);
}

// δ in (−π, π].
inline double wrapped(double turn) {
  double wrapped_turn = std::remainder(turn, 2.0 * kPi);
  if (wrapped_turn <= -kPi) wrapped_turn += 2.0 * kPi;
  return wrapped_turn;
}

}  // namespace direct

struct DirectHeading : PhaseHeading {
  // Σ_k k²|P_k| / Σ|F||F'|: bounds |C''| / Σ|F||F'|.
  double curvature_bound = 0.0;
};

inline DirectHeading direct_relative_heading(const Signature& from, const Signature& to,
                                             int components = -1) {
  using direct::Complex;
  using direct::kPi;
  const int m = pair_components(from, to, components, "take the heading");
  std::vector<Complex> cross(static_cast<std::size_t>(m));
  double norm = 0.0;
  for (int line = 0; line < from.lines(); ++line) {
    for (int k = 1; k < m; ++k) {
      const Complex a = from.coefficient(line, k);
      const Complex b = to.coefficient(line, k);
      cross[static_cast<std::size_t>(k)] += b * std::conj(a);
      norm += std::abs(a) * std::abs(b);
    }
  }
  if (norm <= 0.0) return {};

  // The grid, and how far below its peak's true height a sample may lie: C'' is bounded by
  // B = Σ k²|P_k|, so a sample within h/2 of a peak is at most B·h²/8 below it.
  const int steps = std::max(64, 16 * m);
  const double h = 2.0 * kPi / steps;
  std::vector<double> grid(static_cast<std::size_t>(steps));
  for (int i = 0; i < steps; ++i)
    grid[static_cast<std::size_t>(i)] = direct::correlation(cross, i * h);
  double curvature_bound = 0.0;
  for (int k = 1; k < m; ++k) curvature_bound += double(k) * k * std::abs(cross[std::size_t(k)]);
  const double highest = *std::max_element(grid.begin(), grid.end());
  const double margin = curvature_bound * h * h / 8.0 + 1e-9 * norm;

  double best_turn = 0.0;
  double best_value = -HUGE_VAL;
  for (int i = 0; i < steps; ++i) {
    const double here = grid[static_cast<std::size_t>(i)];
    const double before = grid[static_cast<std::size_t>((i + steps - 1) % steps)];
    const double after = grid[static_cast<std::size_t>((i + 1) % steps)];
    if (here < before || here < after || here < highest - margin) continue;
    double turn = i * h;
    if (direct::slope(cross, (i - 1) * h) > 0.0 && direct::slope(cross, (i + 1) * h) < 0.0) {
      turn = direct::peak_in(cross, (i - 1) * h, (i + 1) * h);
    }
    const double value = direct::correlation(cross, turn);
    if (value > best_value) {
      best_value = value;
      best_turn = turn;
    }
  }
  DirectHeading result;
  result.turn_rad = direct::wrapped(best_turn);
  result.confidence = std::clamp(best_value / norm, -1.0, 1.0);
  result.curvature_bound = curvature_bound / norm;
  return result;
}

}  // namespace omninav::signature::testing
