// The Jacobians Ceres differentiates from the residual functors, against the derivatives worked
// out by hand from the formulas of residuals.hpp (Ceres' pose_graph_2d tests check its analytic
// cost the same way): nothing here shares code with the functors.
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>

#include "omninav/lattice/residuals.hpp"

namespace omninav::lattice {
namespace {

// Evaluates `cost` at (a, b): residuals and both 2-column Jacobian blocks (row-major).
template <int kResiduals>
struct Evaluated {
  std::array<double, kResiduals> residual{};
  std::array<double, 2 * kResiduals> d_a{}, d_b{};
};

template <int kResiduals>
Evaluated<kResiduals> evaluate(const ceres::CostFunction& cost, const std::array<double, 2>& a,
                               const std::array<double, 2>& b) {
  Evaluated<kResiduals> out;
  const double* parameters[] = {a.data(), b.data()};
  double* jacobians[] = {out.d_a.data(), out.d_b.data()};
  EXPECT_TRUE(cost.Evaluate(parameters, out.residual.data(), jacobians));
  return out;
}

TEST(ResidualJacobians, SpringMatchesTheHandDerivative) {
  // r = √K (|a − b| − L): dr/da = √K (a − b)/|a − b|, dr/db = −dr/da.
  const double rest = 1.3, stiffness = 2.5;
  const std::unique_ptr<ceres::CostFunction> cost(SpringResidual::Create(rest, stiffness));
  for (const auto& [a, b] : {std::pair{std::array{0.2, -0.4}, std::array{1.7, 0.9}},
                             std::pair{std::array{-3.0, 2.0}, std::array{-2.5, 2.1}},
                             std::pair{std::array{5.0, 5.0}, std::array{1.0, 8.0}}}) {
    const double dx = a[0] - b[0], dy = a[1] - b[1], length = std::hypot(dx, dy);
    const Evaluated<1> e = evaluate<1>(*cost, a, b);
    EXPECT_NEAR(e.residual[0], std::sqrt(stiffness) * (length - rest), 1e-9);
    EXPECT_NEAR(e.d_a[0], std::sqrt(stiffness) * dx / length, 1e-9);
    EXPECT_NEAR(e.d_a[1], std::sqrt(stiffness) * dy / length, 1e-9);
    EXPECT_NEAR(e.d_b[0], -std::sqrt(stiffness) * dx / length, 1e-9);
    EXPECT_NEAR(e.d_b[1], -std::sqrt(stiffness) * dy / length, 1e-9);
  }
}

TEST(ResidualJacobians, AStretchedAtLeastSpringHasNoGradient) {
  const std::unique_ptr<ceres::CostFunction> cost(SpringResidual::Create(1.0, 4.0, true));
  const Evaluated<1> e = evaluate<1>(*cost, {0.0, 0.0}, {3.0, 4.0});  // 5 m > 1 m
  EXPECT_EQ(e.residual[0], 0.0);
  for (const double d : e.d_a) EXPECT_EQ(d, 0.0);
  for (const double d : e.d_b) EXPECT_EQ(d, 0.0);
}

TEST(ResidualJacobians, MotionMatchesTheHandDerivative) {
  // r0 = (Δ·u − L)/σ_L, r1 = (Δ·u⊥)/(σ_θ L) with Δ = to − from, u = (cos θ, sin θ),
  // u⊥ = (−sin θ, cos θ): linear in the positions, so constant Jacobians ∓u/σ_L, ∓u⊥/(σ_θ L).
  const double theta = 2.2, length = 0.6, sigma_theta = 0.15, sigma_length = 0.05;
  const std::unique_ptr<ceres::CostFunction> cost(
      MotionResidual::Create(theta, length, sigma_theta, sigma_length));
  const double ux = std::cos(theta), uy = std::sin(theta);
  const std::array from{0.4, -1.0}, to{-0.1, -0.3};
  const Evaluated<2> e = evaluate<2>(*cost, from, to);
  const double dx = to[0] - from[0], dy = to[1] - from[1];
  EXPECT_NEAR(e.residual[0], (dx * ux + dy * uy - length) / sigma_length, 1e-9);
  EXPECT_NEAR(e.residual[1], (-dx * uy + dy * ux) / (sigma_theta * length), 1e-9);
  const double across = 1.0 / (sigma_theta * length);
  const std::array<double, 4> d_to{ux / sigma_length, uy / sigma_length, -uy * across, ux * across};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(e.d_b[i], d_to[i], 1e-9) << i;
    EXPECT_NEAR(e.d_a[i], -d_to[i], 1e-9) << i;
  }
}

}  // namespace
}  // namespace omninav::lattice
