#include "omninav/core/angles.hpp"

#include <gtest/gtest.h>

namespace omninav {
namespace {

TEST(WrapAngle, KeepsValuesInsideTheHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(wrap_angle(0.3), 0.3);
  EXPECT_DOUBLE_EQ(wrap_angle(kPi), kPi);   // +π is inside (-π, π]
  EXPECT_DOUBLE_EQ(wrap_angle(-kPi), kPi);  // -π is not: it maps to +π
  EXPECT_NEAR(wrap_angle(3 * kPi), kPi, 1e-12);
  EXPECT_NEAR(wrap_angle(-3 * kPi + 0.1), -kPi + 0.1, 1e-12);
  EXPECT_NEAR(wrap_angle(kTwoPi * 1000 + 0.25), 0.25, 1e-9);
}

TEST(WrapAngle, DegreesMatchRadians) {
  for (double deg = -1000.0; deg <= 1000.0; deg += 7.3) {
    EXPECT_NEAR(deg_to_rad(wrap_angle_deg(deg)), wrap_angle(deg_to_rad(deg)), 1e-9) << deg;
    EXPECT_GT(wrap_angle_deg(deg), -180.0);
    EXPECT_LE(wrap_angle_deg(deg), 180.0);
  }
  EXPECT_DOUBLE_EQ(wrap_angle_deg(-180.0), 180.0);
  EXPECT_DOUBLE_EQ(wrap_angle_deg(540.0), 180.0);
}

TEST(SignedDifference, CrossesTheSeamTheShortWay) {
  // 179° to -179° is a 2° counter-clockwise turn, not -358°.
  EXPECT_NEAR(signed_difference_deg(-179.0, 179.0), 2.0, 1e-12);
  EXPECT_NEAR(signed_difference_deg(179.0, -179.0), -2.0, 1e-12);
  EXPECT_NEAR(signed_difference(deg_to_rad(-179.0), deg_to_rad(179.0)), deg_to_rad(2.0), 1e-12);
  EXPECT_NEAR(signed_difference(deg_to_rad(10.0), deg_to_rad(350.0)), deg_to_rad(20.0), 1e-12);
}

TEST(SignedDifference, AddsBackToTheTarget) {
  for (double from = -7.0; from < 7.0; from += 0.37) {
    for (double to = -7.0; to < 7.0; to += 0.41) {
      const double delta = signed_difference(to, from);
      EXPECT_GT(delta, -kPi);
      EXPECT_LE(delta, kPi);
      EXPECT_NEAR(wrap_angle(from + delta), wrap_angle(to), 1e-9);
    }
  }
}

TEST(DegreesRadians, RoundTrip) {
  EXPECT_DOUBLE_EQ(deg_to_rad(180.0), kPi);
  EXPECT_DOUBLE_EQ(rad_to_deg(kPi / 2), 90.0);
  static_assert(deg_to_rad(0.0) == 0.0);
}

}  // namespace
}  // namespace omninav
