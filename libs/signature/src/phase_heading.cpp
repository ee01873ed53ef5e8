#include "omninav/signature/phase_heading.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::signature {
namespace {

using Complex = std::complex<double>;

// C(δ) = Σ_k Re(P_k e^{ikδ}) and its first two derivatives.
struct Correlation {
  double value = 0.0, first = 0.0, second = 0.0;
};

Correlation correlation_at(const std::vector<Complex>& cross, double turn) {
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

double polish(const std::vector<Complex>& cross, double turn) {
  for (int iteration = 0; iteration < 4; ++iteration) {
    const Correlation c = correlation_at(cross, turn);
    if (!(c.second < 0.0)) break;  // not at a maximum's basin: keep the estimate
    const double step = -c.first / c.second;
    // A Newton step longer than half the finest period would jump to another peak.
    if (std::fabs(step) > kPi / static_cast<double>(cross.size())) break;
    turn += step;
    if (std::fabs(step) < 1e-12) break;
  }
  return wrap_angle(turn);
}

}  // namespace

PhaseHeading relative_heading(const Signature& from, const Signature& to, int components) {
  if (!from.same_layout(to)) {
    throw UsageError("cannot take the heading between signatures of different layouts (" +
                     std::to_string(from.lines()) + " and " + std::to_string(to.lines()) +
                     " lines)");
  }
  const int m = components < 0 ? std::min(from.components, to.components) : components;
  if (m < 2 || m > from.components || m > to.components) {
    throw UsageError("the phase heading needs 2.." +
                     std::to_string(std::min(from.components, to.components)) +
                     " components, got " + std::to_string(m));
  }
  // Cross-power per component and the normaliser Σ |F||F'|.
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
  if (norm <= 0.0) return {};  // flat rows: no heading information at all

  // 1. Coarse, from k = 1.
  double turn = -std::arg(cross[1]);
  double weight_sum = std::abs(cross[1]);
  double weighted = turn * weight_sum;
  // 2. Refined with k = 2..m−1, each on the branch nearest the running estimate.
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
  // 3. Polished on the correlation.
  turn = polish(cross, turn);
  // 4. Guarded by a scan of the whole circle.
  const int steps = 8 * m;
  double best_turn = turn;
  double best_value = correlation_at(cross, turn).value;
  for (int i = 0; i < steps; ++i) {
    const double candidate = -kPi + kTwoPi * (i + 0.5) / steps;
    const double value = correlation_at(cross, candidate).value;
    if (value > best_value + 1e-6 * norm) {
      best_value = value;
      best_turn = candidate;
    }
  }
  if (best_turn != turn) {
    const double polished = polish(cross, best_turn);
    if (correlation_at(cross, polished).value > correlation_at(cross, turn).value) turn = polished;
  }
  PhaseHeading result;
  result.turn_rad = wrap_angle(turn);
  result.confidence = std::clamp(correlation_at(cross, turn).value / norm, -1.0, 1.0);
  return result;
}

}  // namespace omninav::signature
