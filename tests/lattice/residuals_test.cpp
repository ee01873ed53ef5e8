#include "omninav/lattice/residuals.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "omninav/lattice/stiffness.hpp"

namespace omninav::lattice {
namespace {

double spring_residual(double rest, double stiffness, const double* a, const double* b) {
  double residual = 0.0;
  SpringResidual(rest, stiffness)(a, b, &residual);
  return residual;
}

TEST(SpringResidual, ZeroAtRestLengthAndSignedOffIt) {
  const double a[2] = {1.0, 2.0};
  const double b[2] = {4.0, 6.0};  // 5 m apart
  EXPECT_NEAR(spring_residual(5.0, 1.0, a, b), 0.0, 1e-9);
  EXPECT_GT(spring_residual(4.0, 1.0, a, b), 0.0);  // stretched: pulls
  EXPECT_LT(spring_residual(6.0, 1.0, a, b), 0.0);  // compressed: pushes
  // √K scales the residual, so K scales the energy.
  EXPECT_NEAR(spring_residual(4.0, 0.25, a, b), 0.5 * spring_residual(4.0, 1.0, a, b), 1e-12);
}

TEST(SpringResidual, AnAtLeastSpringPushesButNeverPulls) {
  const double a[2] = {1.0, 2.0};
  const double b[2] = {4.0, 6.0};  // 5 m apart
  double residual = 1.0;
  SpringResidual(4.0, 1.0, true)(a, b, &residual);  // stretched past rest: no force
  EXPECT_EQ(residual, 0.0);
  SpringResidual(6.0, 1.0, true)(a, b, &residual);  // compressed: pushes like a spring
  EXPECT_NEAR(residual, spring_residual(6.0, 1.0, a, b), 1e-12);
}

std::array<double, 2> motion_residual(double direction, double length, const double* from,
                                      const double* to) {
  std::array<double, 2> residual{};
  // σ_direction = 0.1 rad, σ_length = 0.5 m: residuals in standard deviations.
  MotionResidual(direction, length, 0.1, 0.5)(from, to, residual.data());
  return residual;
}

TEST(MotionResidual, ZeroAtTheMeasuredStepSignedAlongAndAcrossIt) {
  const double from[2] = {1.0, 1.0};
  const double to[2] = {-1.0, 1.0};  // 2 m along −x
  EXPECT_NEAR(motion_residual(M_PI, 2.0, from, to)[0], 0.0, 1e-12);
  EXPECT_NEAR(motion_residual(M_PI, 2.0, from, to)[1], 0.0, 1e-12);
  EXPECT_NEAR(motion_residual(-M_PI, 2.0, from, to)[1], 0.0, 1e-12);  // across the seam
  // 1 m further than measured: +1 m / σ_length along, nothing across.
  EXPECT_NEAR(motion_residual(M_PI, 1.0, from, to)[0], 2.0, 1e-12);
  EXPECT_NEAR(motion_residual(M_PI, 1.0, from, to)[1], 0.0, 1e-12);
  // 0.2 m to the left of the measured direction (−x): 0.2 / (σ_direction · length) across.
  const double left[2] = {-1.0, 0.8};
  EXPECT_NEAR(motion_residual(M_PI, 2.0, from, left)[1], 1.0, 1e-12);
  const double right[2] = {-1.0, 1.2};
  EXPECT_NEAR(motion_residual(M_PI, 2.0, from, right)[1], -1.0, 1e-12);
  // Unlike an angle, the residual grows when the places fly apart along the direction.
  const double far[2] = {-99.0, 1.0};
  EXPECT_NEAR(motion_residual(M_PI, 2.0, from, far)[0], 196.0, 1e-9);
}

TEST(Stiffness, Equation5) {
  EXPECT_DOUBLE_EQ(spring_stiffness(0.0, 1.2), 1.0);
  EXPECT_NEAR(spring_stiffness(1.2, 1.2), 0.1, 1e-12);  // K(x₁) = 0.1
  EXPECT_LT(spring_stiffness(2.4, 1.2), 1e-3);
  EXPECT_NEAR(spring_stiffness(negligible_length_m(1.2, 1e-3), 1.2), 1e-3, 1e-12);
}

}  // namespace
}  // namespace omninav::lattice
