// The sub-pixel minimum of Labrosse 2006, §3.4.2 (Eqs. 7-12).
#include "omninav/compass/subpixel.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "omninav/core/errors.hpp"

namespace omninav::compass {
namespace {

// A parabola sampled at −1, 0, 1 is recovered exactly by the parabolic fit.
TEST(Subpixel, ParabolicFitIsExactOnAParabola) {
  for (const double vertex : {-0.5, -0.31, 0.0, 0.12, 0.49}) {
    const auto d = [vertex](double x) { return 3.0 + 2.5 * (x - vertex) * (x - vertex); };
    const SubpixelFit fit = parabolic_fit(d(-1), d(0), d(1));
    EXPECT_NEAR(fit.offset_px, vertex, 1e-12);
    EXPECT_NEAR(fit.value, 3.0, 1e-12);
  }
}

// A "V" (two lines of opposite slopes, the sharp minimum of similar images, Fig. 6) sampled at
// −1, 0, 1 is recovered exactly by the linear extrapolation, and not by the parabola.
TEST(Subpixel, LinearExtrapolationIsExactOnAV) {
  for (const double vertex : {-0.5, -0.2, 0.0, 0.37, 0.5}) {
    const auto d = [vertex](double x) { return 1.0 + 4.0 * std::abs(x - vertex); };
    const SubpixelFit fit = linear_fit(d(-1), d(0), d(1));
    EXPECT_NEAR(fit.offset_px, vertex, 1e-12) << vertex;
    EXPECT_NEAR(fit.value, 1.0, 1e-12) << vertex;
    if (vertex != 0.0 && std::abs(vertex) != 0.5) {
      EXPECT_GT(std::abs(parabolic_fit(d(-1), d(0), d(1)).offset_px - vertex), 0.01);
    }
  }
}

// Eqs. 10-11: parabolic up to A_n = 0.5, then p = (A_n − 0.5)/0.5 of the linear fit, all of it
// at A_n = 1, and (our reading) no more than all of it above 1.
TEST(Subpixel, MixtureMovesFromParabolicToLinearWithTheNormalisedAmplitude) {
  const SubpixelParams params;
  EXPECT_EQ(linear_weight(0.2, params), 0.0);
  EXPECT_EQ(linear_weight(0.5, params), 0.0);
  EXPECT_DOUBLE_EQ(linear_weight(0.75, params), 0.5);
  EXPECT_EQ(linear_weight(1.0, params), 1.0);
  EXPECT_EQ(linear_weight(1.7, params), 1.0);
  EXPECT_EQ(linear_weight(std::nan(""), params), 0.0);
  const double d_minus = 9.0, d_0 = 2.0, d_plus = 5.0;
  const SubpixelFit parabolic = parabolic_fit(d_minus, d_0, d_plus);
  const SubpixelFit linear = linear_fit(d_minus, d_0, d_plus);
  const SubpixelFit half = subpixel_fit(d_minus, d_0, d_plus, 0.75, params);
  EXPECT_NEAR(half.offset_px, 0.5 * (parabolic.offset_px + linear.offset_px), 1e-12);
  EXPECT_NEAR(half.value, 0.5 * (parabolic.value + linear.value), 1e-12);
  EXPECT_EQ(subpixel_fit(d_minus, d_0, d_plus, 0.3, params).offset_px, parabolic.offset_px);
  EXPECT_EQ(subpixel_fit(d_minus, d_0, d_plus, 1.0, params).offset_px, linear.offset_px);
  SubpixelParams none = params;
  none.mode = SubpixelMode::kNone;
  EXPECT_EQ(subpixel_fit(d_minus, d_0, d_plus, 0.9, none).offset_px, 0.0);
  EXPECT_EQ(subpixel_fit(d_minus, d_0, d_plus, 0.9, none).value, d_0);
}

// Flat or degenerate shapes never produce a NaN or leave the pixel.
TEST(Subpixel, DegenerateShapesStayOnThePixel) {
  for (const SubpixelMode mode :
       {SubpixelMode::kParabolic, SubpixelMode::kLinear, SubpixelMode::kMixture}) {
    SubpixelParams params;
    params.mode = mode;
    const SubpixelFit flat = subpixel_fit(4.0, 4.0, 4.0, 0.9, params);
    EXPECT_EQ(flat.offset_px, 0.0);
    EXPECT_EQ(flat.value, 4.0);
    const SubpixelFit zero = subpixel_fit(0.0, 0.0, 0.0, 0.0, params);
    EXPECT_EQ(zero.offset_px, 0.0);
    const SubpixelFit one_sided = subpixel_fit(4.0, 4.0, 6.0, 0.9, params);
    EXPECT_TRUE(std::isfinite(one_sided.offset_px));
    EXPECT_LE(std::abs(one_sided.offset_px), 0.5);
  }
}

TEST(Subpixel, ModeNamesRoundTrip) {
  for (const SubpixelMode mode : {SubpixelMode::kNone, SubpixelMode::kParabolic,
                                  SubpixelMode::kLinear, SubpixelMode::kMixture}) {
    EXPECT_EQ(subpixel_mode_of(to_string(mode)), mode);
  }
  EXPECT_THROW(subpixel_mode_of("cubic"), UsageError);
}

}  // namespace
}  // namespace omninav::compass
