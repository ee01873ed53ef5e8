#pragma once
// The oracle for the motion fit's fast evaluation (libs/signature/src/warp_fit.hpp): the same
// least-squares problem evaluated line by line, sample by sample, as estimate_motion() did before
// the identity, in O(N·lines·m), from the problem's definition alone (N = max(16, 4m) column
// angles, the residuals and their Jacobian): none of the fast evaluation's sums. It shares only
// the interface the Levenberg-Marquardt stages call (detail::WarpObjective), so that the stages
// can run on either. Used by tests/signature/motion_test.cpp and
// tests/bench/signature_bench.cpp only.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "../../libs/signature/src/warp_fit.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::signature::testing {

class DirectWarpFit final : public detail::WarpObjective {
  using Complex = std::complex<double>;

 public:
  DirectWarpFit(const Signature& from, const Signature& to, int m)
      : m_(m), lines_(from.lines()), samples_(std::max(16, 4 * m)) {
    to_coefficients_.resize(static_cast<std::size_t>(lines_) * m_);
    for (int line = 0; line < lines_; ++line) {
      for (int k = 1; k < m_; ++k) to_coefficients_[index(line, k)] = to.coefficient(line, k);
    }
    // The target: the low-pass signal of `from` at each sample.
    std::vector<Complex> from_coefficients(static_cast<std::size_t>(lines_) * m_);
    for (int line = 0; line < lines_; ++line) {
      for (int k = 1; k < m_; ++k) from_coefficients[index(line, k)] = from.coefficient(line, k);
    }
    target_.resize(static_cast<std::size_t>(lines_) * samples_);
    cos_u_.resize(samples_);
    sin_u_.resize(samples_);
    double energy = 0.0;
    for (int n = 0; n < samples_; ++n) {
      const double u = kTwoPi * n / samples_;
      cos_u_[n] = std::cos(u);
      sin_u_[n] = std::sin(u);
      for (int line = 0; line < lines_; ++line) {
        double value = 0.0;
        for (int k = 1; k < m_; ++k) {
          value += 2.0 * (from_coefficients[index(line, k)] * std::polar(1.0, k * u)).real();
        }
        target_[static_cast<std::size_t>(line) * samples_ + n] = value;
        energy += value * value;
      }
    }
    signal_rms_ = std::sqrt(energy / static_cast<double>(target_.size()));
  }

  detail::WarpEvaluation evaluate(const Eigen::Vector3d& p) const override {
    detail::WarpEvaluation e;
    std::vector<Complex> powers(static_cast<std::size_t>(m_));
    for (int n = 0; n < samples_; ++n) {
      const double u = kTwoPi * n / samples_;
      const double warped = u + p[0] + p[1] * cos_u_[n] + p[2] * sin_u_[n];
      const Complex step = std::polar(1.0, warped);
      Complex z = step;
      for (int k = 1; k < m_; ++k) {
        powers[static_cast<std::size_t>(k)] = z;
        z *= step;
      }
      const Eigen::Vector3d basis(1.0, cos_u_[n], sin_u_[n]);
      for (int line = 0; line < lines_; ++line) {
        double value = 0.0, derivative = 0.0;
        const Complex* c = &to_coefficients_[index(line, 0)];
        for (int k = 1; k < m_; ++k) {
          const Complex t = c[k] * powers[static_cast<std::size_t>(k)];
          value += t.real();
          derivative -= k * t.imag();
        }
        const double residual =
            2.0 * value - target_[static_cast<std::size_t>(line) * samples_ + n];
        e.cost += residual * residual;
        const Eigen::Vector3d jacobian = (2.0 * derivative) * basis;
        e.normal.noalias() += jacobian * jacobian.transpose();
        e.gradient.noalias() += jacobian * residual;
      }
    }
    return e;
  }

  std::size_t residual_count() const override { return target_.size(); }
  double signal_rms() const override { return signal_rms_; }

 private:
  std::size_t index(int line, int k) const {
    return static_cast<std::size_t>(line) * m_ + static_cast<std::size_t>(k);
  }
  int m_;
  int lines_;
  int samples_;
  std::vector<Complex> to_coefficients_;
  std::vector<double> target_;
  std::vector<double> cos_u_, sin_u_;
  double signal_rms_ = 0.0;
};

// estimate_motion() as it was: the same stages, each evaluated line by line.
inline MotionEstimate direct_estimate_motion(const Signature& from, const Signature& to, int m,
                                             std::optional<double> known_turn_rad = std::nullopt) {
  return detail::fit_motion(
      from, to, m, [&](int stage_m) { return std::make_unique<DirectWarpFit>(from, to, stage_m); },
      known_turn_rad);
}

}  // namespace omninav::signature::testing
