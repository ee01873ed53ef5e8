#include "omninav/signature/phase_heading.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <vector>

#include "fast_math.hpp"
#include "omninav/core/angles.hpp"

namespace omninav::signature {
namespace {

// The turn from the cross-power's branches (phase_heading.hpp, steps 1-2): k = 1 gives it
// without ambiguity, then each k = 2..m−1 refines it on the branch of its arg(P_k)/k nearest the
// running estimate, weighted by k·|P_k|. `cross_at(k)` returns P_k for k = 1..m−1.
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

// The cross-power P_k (k = 0..m−1, P_0 unused) as separate real and imaginary parts.
struct CrossPower {
  std::vector<double> re, im;
  std::size_t size() const { return re.size(); }
};

// C(δ) = Σ_k Re(P_k e^{ikδ}) and its first two derivatives.
struct Correlation {
  double value = 0.0, first = 0.0, second = 0.0;
};

// e^{ikδ} as the k-th power of e^{iδ}: one sincos per evaluation instead of one per component.
// Each product adds about one rounding, so e^{ikδ} is off by ~k·2e-16: 1.3e-14 at m = 64,
// 6e-14 at m = 300. phase_heading_test.cpp compares the turn with the direct form's.
Correlation correlation_at(const CrossPower& cross, double turn) {
  double step_sin = 0.0, step_cos = 0.0;
  detail::sin_cos(&turn, 1, &step_sin, &step_cos);
  double power_re = step_cos, power_im = step_sin;  // e^{ikδ}, from k = 1
  Correlation c;
  for (std::size_t k = 1; k < cross.size(); ++k) {
    const double rotated_re = cross.re[k] * power_re - cross.im[k] * power_im;
    const double rotated_im = cross.re[k] * power_im + cross.im[k] * power_re;
    const double kk = static_cast<double>(k);
    c.value += rotated_re;
    c.first -= kk * rotated_im;
    c.second -= kk * kk * rotated_re;
    const double next_re = power_re * step_cos - power_im * step_sin;
    power_im = power_re * step_sin + power_im * step_cos;
    power_re = next_re;
  }
  return c;
}

double polish(const CrossPower& cross, double turn) {
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

// C at the grid turns δ_i = −π + 2π(i + ½)/S, i = 0..S−1. With Q_k = P_k·e^{ik(π/S − π)},
// C(δ_i) = Σ_k Re(Q_k·e^{2πi·(k·i mod S)/S}): S + m sincos for the whole grid, where evaluating
// C at each turn would take S·m (or S with powers).
std::vector<double> correlation_on_grid(const CrossPower& cross, int steps) {
  const std::size_t m = cross.size(), S = static_cast<std::size_t>(steps);
  // Angles kπ/S (k = 1..m−1) then 2πj/S (j = 0..S−1), their sines and cosines in one call.
  std::vector<double> angles(m - 1 + S), sines(angles.size()), cosines(angles.size());
  for (std::size_t k = 1; k < m; ++k) {
    angles[k - 1] = kPi * static_cast<double>(k) / static_cast<double>(steps);
  }
  for (std::size_t j = 0; j < S; ++j) {
    angles[m - 1 + j] = kTwoPi * static_cast<double>(j) / static_cast<double>(steps);
  }
  detail::sin_cos(angles.data(), angles.size(), sines.data(), cosines.data());
  const double* twiddle_sin = sines.data() + (m - 1);
  const double* twiddle_cos = cosines.data() + (m - 1);
  // Q_k, using e^{−ikπ} = (−1)^k.
  std::vector<double> q_re(m), q_im(m);
  for (std::size_t k = 1; k < m; ++k) {
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    q_re[k] = sign * (cross.re[k] * cosines[k - 1] - cross.im[k] * sines[k - 1]);
    q_im[k] = sign * (cross.re[k] * sines[k - 1] + cross.im[k] * cosines[k - 1]);
  }
  std::vector<double> values(S);
  for (std::size_t i = 0; i < S; ++i) {
    double value = 0.0;
    std::size_t j = i;  // k·i mod S, for k = 1 first
    for (std::size_t k = 1; k < m; ++k) {
      value += q_re[k] * twiddle_cos[j] - q_im[k] * twiddle_sin[j];
      j += i;
      if (j >= S) j -= S;
    }
    values[i] = value;
  }
  return values;
}

// The cross-power P_k = Σ_lines F'_k·conj(F_k), k = 1..m−1, into `cross`, and the normaliser
// Σ |F||F'| returned: straight from the stored magnitudes and phases, F'·conj(F) =
// |F||F'|·e^{i(φ' − φ)}, one sincos per pair. In batches of whole lines (or of a line's
// components, for m > kBatch) for the vectorised sin_cos, small enough to stay on the stack and
// in the L1 cache; the sums run along k, so that they vectorise too, and the normaliser is
// summed per component (one long chain of additions would be its latency).
double cross_power(const Signature& from, const Signature& to, int m, CrossPower& cross) {
  cross.re.assign(static_cast<std::size_t>(m), 0.0);
  cross.im.assign(static_cast<std::size_t>(m), 0.0);
  std::vector<double> norm_k(static_cast<std::size_t>(m));
  {
    constexpr int kBatch = 256;
    std::array<double, kBatch> angle, weight, sine, cosine;
    const int span = std::min(m - 1, kBatch);  // components per line in one batch
    const int lines_per_batch = kBatch / span;
    for (int k0 = 1; k0 < m; k0 += span) {
      const int width = std::min(span, m - k0);
      for (int line0 = 0; line0 < from.lines(); line0 += lines_per_batch) {
        const int batch_lines = std::min(lines_per_batch, from.lines() - line0);
        for (int l = 0; l < batch_lines; ++l) {
          const float* from_magnitude = &from.magnitude[from.at(line0 + l, k0)];
          const float* from_phase = &from.phase_rad[from.at(line0 + l, k0)];
          const float* to_magnitude = &to.magnitude[to.at(line0 + l, k0)];
          const float* to_phase = &to.phase_rad[to.at(line0 + l, k0)];
          double* line_angle = angle.data() + l * width;
          double* line_weight = weight.data() + l * width;
          for (int j = 0; j < width; ++j) {
            line_angle[j] = static_cast<double>(to_phase[j]) - static_cast<double>(from_phase[j]);
            line_weight[j] = static_cast<double>(from_magnitude[j]) * to_magnitude[j];
          }
        }
        const std::size_t count = static_cast<std::size_t>(batch_lines) * width;
        detail::sin_cos(angle.data(), count, sine.data(), cosine.data());
        double* __restrict re = cross.re.data() + k0;
        double* __restrict im = cross.im.data() + k0;
        double* __restrict norm_part = norm_k.data() + k0;
        for (int l = 0; l < batch_lines; ++l) {
          const std::size_t offset = static_cast<std::size_t>(l) * width;
          for (int j = 0; j < width; ++j) {
            re[j] += weight[offset + j] * cosine[offset + j];
            im[j] += weight[offset + j] * sine[offset + j];
            norm_part[j] += weight[offset + j];
          }
        }
      }
    }
  }
  double norm = 0.0;
  for (int k = 1; k < m; ++k) norm += norm_k[static_cast<std::size_t>(k)];
  return norm;
}

}  // namespace

PhaseHeading relative_heading(const Signature& from, const Signature& to, int components) {
  const int m = pair_components(from, to, components, "take the heading");
  CrossPower cross;
  const double norm = cross_power(from, to, m, cross);
  if (norm <= 0.0) return {};  // flat rows: no heading information at all
  const auto at = [&](int k) {
    return std::complex<double>(cross.re[static_cast<std::size_t>(k)],
                                cross.im[static_cast<std::size_t>(k)]);
  };

  // 1-2. From the phases of k = 1, refined with k = 2..m−1.
  double turn = turn_from_branches(at, m);
  // 3. Polished on the correlation.
  turn = polish(cross, turn);
  double value = correlation_at(cross, turn).value;
  // 4. Guarded by a scan of the whole circle.
  const int steps = 8 * m;
  const std::vector<double> grid = correlation_on_grid(cross, steps);
  double best_turn = turn;
  double best_value = value;
  for (int i = 0; i < steps; ++i) {
    if (grid[static_cast<std::size_t>(i)] > best_value + 1e-6 * norm) {
      best_value = grid[static_cast<std::size_t>(i)];
      best_turn = -kPi + kTwoPi * (i + 0.5) / steps;
    }
  }
  if (best_turn != turn) {
    const double polished = polish(cross, best_turn);
    const double polished_value = correlation_at(cross, polished).value;
    if (polished_value > value) {
      turn = polished;
      value = polished_value;
    }
  }
  PhaseHeading result;
  result.turn_rad = wrap_angle(turn);
  result.confidence = std::clamp(value / norm, -1.0, 1.0);
  return result;
}

}  // namespace omninav::signature
