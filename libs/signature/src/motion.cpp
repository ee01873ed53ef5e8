#include "omninav/signature/motion.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/signature/phase_heading.hpp"

namespace omninav::signature {
namespace {

using Complex = std::complex<double>;

// The least-squares problem of motion.hpp on components 1..m−1, sampled at N column angles.
class WarpFit {
 public:
  WarpFit(const Signature& from, const Signature& to, int m)
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

  struct Evaluation {
    double cost = 0.0;
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();    // JᵀJ
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero();  // Jᵀr
  };

  Evaluation evaluate(const Eigen::Vector3d& p, bool with_derivatives) const {
    Evaluation e;
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
        if (with_derivatives) {
          const Eigen::Vector3d jacobian = (2.0 * derivative) * basis;
          e.normal.noalias() += jacobian * jacobian.transpose();
          e.gradient.noalias() += jacobian * residual;
        }
      }
    }
    return e;
  }

  // Levenberg-Marquardt from `start`; returns the parameters and their final evaluation.
  std::pair<Eigen::Vector3d, Evaluation> solve(Eigen::Vector3d p) const {
    Evaluation current = evaluate(p, true);
    double lambda = 1e-3;
    for (int iteration = 0; iteration < 30; ++iteration) {
      Eigen::Matrix3d damped = current.normal;
      damped.diagonal() *= 1.0 + lambda;
      damped.diagonal().array() += 1e-12;
      const Eigen::Vector3d step = damped.ldlt().solve(-current.gradient);
      if (!step.allFinite()) break;
      const Eigen::Vector3d candidate = p + step;
      const Evaluation next = evaluate(candidate, true);
      if (next.cost < current.cost) {
        p = candidate;
        const bool converged = current.cost - next.cost < 1e-9 * current.cost;
        current = next;
        lambda = std::max(lambda * 0.3, 1e-7);
        if (converged || step.norm() < 1e-7) break;
      } else {
        lambda *= 10.0;
        if (lambda > 1e8) break;
      }
    }
    return {p, current};
  }

  std::size_t residual_count() const { return target_.size(); }
  double signal_rms() const { return signal_rms_; }

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

}  // namespace

MotionEstimate estimate_motion(const Signature& from, const Signature& to, int components) {
  if (!from.same_layout(to)) {
    throw UsageError("cannot estimate motion between signatures of different layouts (" +
                     std::to_string(from.lines()) + " and " + std::to_string(to.lines()) +
                     " lines)");
  }
  const int m = components < 0 ? std::min(from.components, to.components) : components;
  if (m < 2 || m > from.components || m > to.components) {
    throw UsageError("motion estimation needs 2.." +
                     std::to_string(std::min(from.components, to.components)) +
                     " components, got " + std::to_string(m));
  }
  const double turn = relative_heading(from, to, m).turn_rad;

  // Stage 1, components 1..3: five starts, the best kept.
  const int coarse_m = std::min(m, 4);
  const WarpFit coarse(from, to, coarse_m);
  constexpr double kStartParallax = 0.1;  // rad: d/r for 30 cm steps 3 m from the walls
  std::array<Eigen::Vector3d, 5> starts = {
      Eigen::Vector3d(turn, 0.0, 0.0), Eigen::Vector3d(turn, -kStartParallax, 0.0),
      Eigen::Vector3d(turn, kStartParallax, 0.0), Eigen::Vector3d(turn, 0.0, kStartParallax),
      Eigen::Vector3d(turn, 0.0, -kStartParallax)};
  Eigen::Vector3d best = starts[0];
  double best_cost = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& start : starts) {
    const auto [p, evaluation] = coarse.solve(start);
    if (evaluation.cost < best_cost) {
      best_cost = evaluation.cost;
      best = p;
    }
  }
  // Stages 2 and 3: more components, each from the previous fit.
  std::pair<Eigen::Vector3d, WarpFit::Evaluation> fit{best, {}};
  const WarpFit* last = &coarse;
  std::optional<WarpFit> middle, fine;
  if (m > coarse_m) {
    const int middle_m = std::min(m, 8);
    middle.emplace(from, to, middle_m);
    fit = middle->solve(fit.first);
    last = &*middle;
    if (m > middle_m) {
      fine.emplace(from, to, m);
      fit = fine->solve(fit.first);
      last = &*fine;
    }
  } else {
    fit = coarse.solve(best);
  }

  const Eigen::Vector3d& p = fit.first;
  const WarpFit::Evaluation& evaluation = fit.second;
  MotionEstimate estimate;
  estimate.turn_rad = wrap_angle(p[0]);
  const double b = p[1], c = p[2];
  const double rho = std::hypot(b, c);
  estimate.parallax_rad = rho;
  estimate.bearing_rad = wrap_angle(std::atan2(c, -b));
  const double count = static_cast<double>(last->residual_count());
  const double rms = std::sqrt(evaluation.cost / count);
  estimate.residual = last->signal_rms() > 0.0 ? rms / last->signal_rms() : 1.0;
  // Covariance σ²(JᵀJ)⁻¹; neighbouring samples of a low-pass signal are correlated, so this
  // is optimistic, which the 3σ rule below allows for only roughly.
  const double variance = evaluation.cost / std::max(1.0, count - 3.0);
  const Eigen::Matrix3d covariance =
      variance * (evaluation.normal + 1e-12 * Eigen::Matrix3d::Identity()).inverse();
  if (rho > 0.0 && covariance.allFinite()) {
    const Eigen::Vector2d along(b / rho, c / rho);
    const Eigen::Vector2d across(c / (rho * rho), -b / (rho * rho));
    const Eigen::Matrix2d bc = covariance.bottomRightCorner<2, 2>();
    const double rho_sd = std::sqrt(std::max(0.0, along.dot(bc * along)));
    estimate.bearing_stddev_rad =
        std::min(MotionEstimate::kNoBearing, std::sqrt(std::max(0.0, across.dot(bc * across))));
    estimate.valid = rho > 3.0 * rho_sd;
  }
  return estimate;
}

}  // namespace omninav::signature
