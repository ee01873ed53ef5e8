#include "omninav/signature/motion.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "omninav/core/angles.hpp"
#include "omninav/signature/phase_heading.hpp"
#include "warp_fit.hpp"

namespace omninav::signature {
namespace detail {
namespace {

// Levenberg-Marquardt from `p`; returns the parameters and their final evaluation. With
// `turn_known`, τ = p[0] stays where it is and only the translation (b, c) is fitted.
std::pair<Eigen::Vector3d, WarpEvaluation> solve(const WarpObjective& objective, Eigen::Vector3d p,
                                                 bool turn_known) {
  WarpEvaluation current = objective.evaluate(p);
  double lambda = 1e-3;
  for (int iteration = 0; iteration < 30; ++iteration) {
    Eigen::Matrix3d damped = current.normal;
    damped.diagonal() *= 1.0 + lambda;
    damped.diagonal().array() += 1e-12;
    Eigen::Vector3d step = Eigen::Vector3d::Zero();
    if (turn_known) {
      step.tail<2>() = damped.bottomRightCorner<2, 2>().ldlt().solve(-current.gradient.tail<2>());
    } else {
      step = damped.ldlt().solve(-current.gradient);
    }
    if (!step.allFinite()) break;
    const Eigen::Vector3d candidate = p + step;
    const WarpEvaluation next = objective.evaluate(candidate);
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

}  // namespace

MotionEstimate fit_motion(const Signature& from, const Signature& to, int m,
                          const ObjectiveFactory& objective, std::optional<double> known_turn) {
  const bool turn_known = known_turn.has_value();
  const double turn = turn_known ? *known_turn : relative_heading(from, to, m).turn_rad;

  // Stage 1, components 1..3: five starts, the best kept.
  const int coarse_m = std::min(m, 4);
  const std::unique_ptr<WarpObjective> coarse = objective(coarse_m);
  constexpr double kStartParallax = 0.1;  // rad: d/r for 30 cm steps 3 m from the walls
  std::array<Eigen::Vector3d, 5> starts = {
      Eigen::Vector3d(turn, 0.0, 0.0), Eigen::Vector3d(turn, -kStartParallax, 0.0),
      Eigen::Vector3d(turn, kStartParallax, 0.0), Eigen::Vector3d(turn, 0.0, kStartParallax),
      Eigen::Vector3d(turn, 0.0, -kStartParallax)};
  Eigen::Vector3d best = starts[0];
  double best_cost = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& start : starts) {
    const auto [p, evaluation] = solve(*coarse, start, turn_known);
    if (evaluation.cost < best_cost) {
      best_cost = evaluation.cost;
      best = p;
    }
  }
  // Stages 2 and 3: more components, each from the previous fit.
  std::pair<Eigen::Vector3d, WarpEvaluation> fit{best, {}};
  const WarpObjective* last = coarse.get();
  std::unique_ptr<WarpObjective> middle, fine;
  if (m > coarse_m) {
    const int middle_m = std::min(m, 8);
    middle = objective(middle_m);
    fit = solve(*middle, fit.first, turn_known);
    last = middle.get();
    if (m > middle_m) {
      fine = objective(m);
      fit = solve(*fine, fit.first, turn_known);
      last = fine.get();
    }
  } else {
    fit = solve(*coarse, best, turn_known);
  }

  const Eigen::Vector3d& p = fit.first;
  const WarpEvaluation& evaluation = fit.second;
  MotionEstimate estimate;
  estimate.turn_rad = wrap_angle(p[0]);
  const double b = p[1], c = p[2];
  const double rho = std::hypot(b, c);
  estimate.parallax_rad = rho;
  estimate.bearing_rad = wrap_angle(std::atan2(c, -b));
  const double count = static_cast<double>(last->residual_count());
  const double rms = std::sqrt(evaluation.cost / count);
  estimate.residual = last->signal_rms() > 0.0 ? rms / last->signal_rms() : 1.0;
  // Covariance σ²(JᵀJ)⁻¹ of (b, c) (given τ when the turn is known); neighbouring samples of a
  // low-pass signal are correlated, so this is optimistic, which the 3σ rule below allows for
  // only roughly.
  const int fitted = turn_known ? 2 : 3;
  const double variance = evaluation.cost / std::max(1.0, count - fitted);
  Eigen::Matrix2d bc;
  if (turn_known) {
    bc = variance *
         (evaluation.normal.bottomRightCorner<2, 2>() + 1e-12 * Eigen::Matrix2d::Identity())
             .inverse();
  } else {
    const Eigen::Matrix3d covariance =
        variance * (evaluation.normal + 1e-12 * Eigen::Matrix3d::Identity()).inverse();
    bc = covariance.bottomRightCorner<2, 2>();
  }
  if (rho > 0.0 && bc.allFinite()) {
    const Eigen::Vector2d along(b / rho, c / rho);
    const Eigen::Vector2d across(c / (rho * rho), -b / (rho * rho));
    const double rho_sd = std::sqrt(std::max(0.0, along.dot(bc * along)));
    estimate.bearing_stddev_rad =
        std::min(MotionEstimate::kNoBearing, std::sqrt(std::max(0.0, across.dot(bc * across))));
    estimate.valid = rho > 3.0 * rho_sd;
  }
  return estimate;
}

}  // namespace detail

MotionEstimate estimate_motion(const Signature& from, const Signature& to, int components,
                               std::optional<double> known_turn_rad) {
  const int m = pair_components(from, to, components, "estimate motion");
  const detail::LineSums sums(from, to, m);
  return detail::fit_motion(
      from, to, m,
      [&sums](int stage_m) { return std::make_unique<detail::WarpFit>(sums, stage_m); },
      known_turn_rad);
}

}  // namespace omninav::signature
