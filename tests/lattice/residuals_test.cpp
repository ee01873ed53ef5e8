#include "omninav/lattice/residuals.hpp"

#include <gtest/gtest.h>

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

double motion_residual(double direction, const double* from, const double* to) {
  double residual = 0.0;
  MotionDirectionResidual(direction, 1.0)(from, to, &residual);
  return residual;
}

TEST(MotionDirectionResidual, ZeroAlongTheDirectionSignedAcrossAndWrapped) {
  const double from[2] = {0.0, 0.0};
  const double to[2] = {-1.0, 0.0};  // a step along −x
  EXPECT_NEAR(motion_residual(M_PI, from, to), 0.0, 1e-12);
  EXPECT_NEAR(motion_residual(-M_PI + 1e-9, from, to), 0.0, 1e-8);  // across the seam
  const double ccw[2] = {-1.0, -0.1};  // at −174.3°: 5.7° counter-clockwise of −x
  EXPECT_NEAR(motion_residual(M_PI, from, ccw), std::atan(0.1), 1e-12);
  const double cw[2] = {-1.0, 0.1};  // at 174.3°: clockwise of −x
  EXPECT_NEAR(motion_residual(M_PI, from, cw), -std::atan(0.1), 1e-12);
  EXPECT_NEAR(motion_residual(M_PI / 2, from, to), M_PI / 2, 1e-12);
}

TEST(Stiffness, Equation5) {
  EXPECT_DOUBLE_EQ(spring_stiffness(0.0, 1.2), 1.0);
  EXPECT_NEAR(spring_stiffness(1.2, 1.2), 0.1, 1e-12);  // K(x₁) = 0.1
  EXPECT_LT(spring_stiffness(2.4, 1.2), 1e-3);
  EXPECT_NEAR(spring_stiffness(negligible_length_m(1.2, 1e-3), 1.2), 1e-3, 1e-12);
}

}  // namespace
}  // namespace omninav::lattice
