#pragma once
// The oracle for relative_heading() (libs/signature/src/phase_heading.cpp): the computation as
// it was before it was made faster, one std::polar per coefficient and per term of the
// correlation (the first estimate from the phases' branches, which the speed-up left alone, is
// shared: src/phase_branches.hpp). Used by tests/signature/phase_heading_test.cpp and
// tests/bench/signature_bench.cpp only.

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "../../libs/signature/src/phase_branches.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/signature/phase_heading.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::signature::testing {
namespace direct {

using Complex = std::complex<double>;

struct Correlation {
  double value = 0.0, first = 0.0, second = 0.0;
};

inline Correlation correlation_at(const std::vector<Complex>& cross, double turn) {
  Correlation c;
  for (std::size_t k = 1; k < cross.size(); ++k) {
    const Complex rotated = cross[k] * std::polar(1.0, static_cast<double>(k) * turn);
    const double kk = static_cast<double>(k);
    c.value += rotated.real();
    c.first -= kk * rotated.imag();
    c.second -= kk * kk * rotated.real();
  }
  return c;
}

inline double polish(const std::vector<Complex>& cross, double turn) {
  for (int iteration = 0; iteration < 4; ++iteration) {
    const Correlation c = correlation_at(cross, turn);
    if (!(c.second < 0.0)) break;
    const double step = -c.first / c.second;
    if (std::fabs(step) > kPi / static_cast<double>(cross.size())) break;
    turn += step;
    if (std::fabs(step) < 1e-12) break;
  }
  return wrap_angle(turn);
}

}  // namespace direct

inline PhaseHeading direct_relative_heading(const Signature& from, const Signature& to,
                                            int components = -1) {
  using direct::Complex;
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

  double turn =
      detail::turn_from_branches([&cross](int k) { return cross[static_cast<std::size_t>(k)]; }, m);
  turn = direct::polish(cross, turn);
  const int steps = 8 * m;
  double best_turn = turn;
  double best_value = direct::correlation_at(cross, turn).value;
  for (int i = 0; i < steps; ++i) {
    const double candidate = -kPi + kTwoPi * (i + 0.5) / steps;
    const double value = direct::correlation_at(cross, candidate).value;
    if (value > best_value + 1e-6 * norm) {
      best_value = value;
      best_turn = candidate;
    }
  }
  if (best_turn != turn) {
    const double polished = direct::polish(cross, best_turn);
    if (direct::correlation_at(cross, polished).value > direct::correlation_at(cross, turn).value) {
      turn = polished;
    }
  }
  PhaseHeading result;
  result.turn_rad = wrap_angle(turn);
  result.confidence = std::clamp(direct::correlation_at(cross, turn).value / norm, -1.0, 1.0);
  return result;
}

}  // namespace omninav::signature::testing
