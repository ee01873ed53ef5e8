#include "omninav/measures/error_stats.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::measures {
namespace {

std::vector<double> radians(std::initializer_list<double> degrees) {
  std::vector<double> out;
  for (double d : degrees) out.push_back(deg_to_rad(d));
  return out;
}

TEST(AngularErrors, WrapAcrossTheSeam) {
  // 179° against −179° is 2° short of the truth, not 358° beyond it.
  const std::vector<double> errors =
      angular_errors(radians({179.0, -179.0, 180.0, 10.0}), radians({-179.0, 179.0, -180.0, 5.0}));
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_NEAR(rad_to_deg(errors[0]), -2.0, 1e-12);
  EXPECT_NEAR(rad_to_deg(errors[1]), 2.0, 1e-12);
  EXPECT_NEAR(rad_to_deg(errors[2]), 0.0, 1e-12);
  EXPECT_NEAR(rad_to_deg(errors[3]), 5.0, 1e-12);
}

TEST(AngularErrorStats, HandComputedAcrossTheSeam) {
  // Errors: 170 − (−170) = 340 → −20°, −175 − 175 = −350 → +10°, 10 − 5 = +5°.
  // mean = −5/3°; deviations −55/3, 35/3, 20/3 → sample variance (3025 + 1225 + 400)/9/2;
  // rms = sqrt((400 + 100 + 25)/3); max |e| = 20°.
  const ErrorStats stats = in_degrees(
      angular_error_stats(radians({170.0, -175.0, 10.0}), radians({-170.0, 175.0, 5.0})));
  EXPECT_EQ(stats.count, 3u);
  EXPECT_NEAR(stats.max_abs, 20.0, 1e-10);
  EXPECT_NEAR(stats.mean, -5.0 / 3.0, 1e-10);
  EXPECT_NEAR(stats.stddev, std::sqrt(4650.0 / 18.0), 1e-10);
  EXPECT_NEAR(stats.rms, std::sqrt(175.0), 1e-10);
}

TEST(ErrorStats, HandComputedPlainNumbers) {
  // {1, 2, 3, 4, 10} m: mean 4; deviations −3 −2 −1 0 6, squares sum 50, sample variance
  // 50/4 (n − 1); rms sqrt(130/5); max 10. Not wrapped: 10 stays 10 whatever the unit.
  const std::vector<double> errors = {1.0, 2.0, 3.0, 4.0, 10.0};
  const ErrorStats stats = error_stats(errors);
  EXPECT_EQ(stats.count, 5u);
  EXPECT_DOUBLE_EQ(stats.max_abs, 10.0);
  EXPECT_DOUBLE_EQ(stats.mean, 4.0);
  EXPECT_NEAR(stats.stddev, std::sqrt(12.5), 1e-12);
  EXPECT_NEAR(stats.rms, std::sqrt(26.0), 1e-12);
}

TEST(ErrorStats, MaxAbsTakesNegativeErrors) {
  const std::vector<double> errors = {0.5, -3.0, 1.0};
  EXPECT_DOUBLE_EQ(error_stats(errors).max_abs, 3.0);
}

TEST(ErrorStats, SampleStddevUndefinedForOneError) {
  const std::vector<double> errors = {0.25};
  const ErrorStats stats = error_stats(errors);
  EXPECT_EQ(stats.count, 1u);
  EXPECT_DOUBLE_EQ(stats.mean, 0.25);
  EXPECT_TRUE(std::isnan(stats.stddev));
}

TEST(ErrorStats, LargeBiasDoesNotSwampTheSpread) {
  // E[e²] − mean² would lose the 1e-6 spread under a bias of 1e4; two passes keep it.
  const std::vector<double> errors = {1e4 - 1e-6, 1e4 + 1e-6};
  EXPECT_NEAR(error_stats(errors).stddev, std::sqrt(2.0) * 1e-6, 1e-12);
}

TEST(ErrorStats, RejectsBadInput) {
  EXPECT_THROW(error_stats(std::vector<double>{}), UsageError);
  EXPECT_THROW(error_stats(std::vector<double>{1.0, std::nan("")}), UsageError);
  EXPECT_THROW(angular_errors(std::vector<double>{1.0, 2.0}, std::vector<double>{1.0}), UsageError);
  EXPECT_THROW(angular_errors(std::vector<double>{INFINITY}, std::vector<double>{1.0}), UsageError);
}

TEST(ErrorStats, InDegreesConvertsEveryAngle) {
  const ErrorStats rad{4, kPi, kPi / 2, kPi / 4, kPi / 3};
  const ErrorStats deg = in_degrees(rad);
  EXPECT_EQ(deg.count, 4u);
  EXPECT_NEAR(deg.max_abs, 180.0, 1e-12);
  EXPECT_NEAR(deg.mean, 90.0, 1e-12);
  EXPECT_NEAR(deg.stddev, 45.0, 1e-12);
  EXPECT_NEAR(deg.rms, 60.0, 1e-12);
}

}  // namespace
}  // namespace omninav::measures
