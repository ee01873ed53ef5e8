#pragma once
// The oracle for relative_heading() (libs/signature/src/phase_heading.cpp): the computation as
// it was before it was made faster, one std::polar per coefficient and per term of the
// correlation. Used by tests/signature/phase_heading_test.cpp and tests/bench/signature_bench.cpp
// only.

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
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
  if (!from.same_layout(to)) {
    throw UsageError("cannot take the heading between signatures of different layouts");
  }
  const int m = components < 0 ? std::min(from.components, to.components) : components;
  if (m < 2 || m > from.components || m > to.components) {
    throw UsageError("the phase heading needs 2.." +
                     std::to_string(std::min(from.components, to.components)) +
                     " components, got " + std::to_string(m));
  }
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

  double turn = -std::arg(cross[1]);
  double weight_sum = std::abs(cross[1]);
  double weighted = turn * weight_sum;
  for (int k = 2; k < m; ++k) {
    const Complex p = cross[static_cast<std::size_t>(k)];
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
  turn = weight_sum > 0.0 ? weighted / weight_sum : turn;
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
