#include "omninav/measures/robust_regression.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "omninav/core/errors.hpp"

namespace omninav::measures {
namespace {

// The oracle beside Theil–Sen: ordinary least squares, which outliers pull.
LineFit least_squares_fit(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  const double mean_x = std::accumulate(x.begin(), x.end(), 0.0) / n;
  const double mean_y = std::accumulate(y.begin(), y.end(), 0.0) / n;
  double sxx = 0.0;
  double sxy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mean_x) * (x[i] - mean_x);
    sxy += (x[i] - mean_x) * (y[i] - mean_y);
  }
  return {mean_y - sxy / sxx * mean_x, sxy / sxx};
}

// Forces the bisection-by-counting path whatever the size.
constexpr TheilSenParams kByCounting{.max_exact_points = 0};

TEST(TheilSen, ExactOnNoiselessLine) {
  // Unevenly spaced x, as frame times are: the line is recovered to rounding.
  std::vector<double> x, y;
  for (int i = 0; i < 60; ++i) {
    x.push_back(0.1 * i + 0.013 * (i % 7));
    y.push_back(2.5 - 0.3 * x.back());
  }
  for (const TheilSenParams& params : {TheilSenParams{}, kByCounting}) {
    const LineFit fit = theil_sen_fit(x, y, params);
    EXPECT_NEAR(fit.slope, -0.3, 1e-12);
    EXPECT_NEAR(fit.intercept, 2.5, 1e-12);
  }
}

// A compass error drifting at 0.02 rad/s with 5 mrad of noise over 20 s, whose last quarter
// jumped by 2 rad (as GRASS1 did after frame 700, Labrosse 2006, §4).
struct DriftWithJump {
  std::vector<double> time_s, error_rad;
  static constexpr double kSlope = 0.02;
  static constexpr double kIntercept = 0.01;
};

DriftWithJump drift_with_jump(int n) {
  DriftWithJump data;
  std::mt19937 rng(12345);  // seeded: the same data every run
  std::normal_distribution<double> noise(0.0, 0.005);
  for (int i = 0; i < n; ++i) {
    const double t = 20.0 * i / n;
    double e = DriftWithJump::kIntercept + DriftWithJump::kSlope * t + noise(rng);
    if (i >= n - n / 4) e += 2.0;  // 25 % gross outliers, all at the end
    data.time_s.push_back(t);
    data.error_rad.push_back(e);
  }
  return data;
}

TEST(TheilSen, ResistsAQuarterOfGrossOutliersWhereLeastSquaresDoesNot) {
  const DriftWithJump data = drift_with_jump(200);
  const LineFit least_squares = least_squares_fit(data.time_s, data.error_rad);
  const LineFit theil_sen = theil_sen_fit(data.time_s, data.error_rad);
  // A jump of h at three quarters of a span L pulls the least-squares slope by about
  // 1.125·h/L = 0.11 rad/s, five times the true slope.
  EXPECT_GT(std::abs(least_squares.slope - DriftWithJump::kSlope), 0.05);
  // Theil–Sen: the 37.5 % of pairs straddling the jump all lie above the median, which moves
  // to about the 80th percentile of the clean pairwise slopes, whose spread is σ√2/Δt ≈ 1e-3:
  // within 0.003 rad/s (15 %) of the truth, against 0.11 for least squares.
  EXPECT_NEAR(theil_sen.slope, DriftWithJump::kSlope, 0.003);
  EXPECT_NEAR(theil_sen.intercept, DriftWithJump::kIntercept, 0.05);
}

TEST(TheilSen, DeterministicAndBothPathsAgree) {
  // Random data with ties in x (x on a 0.5 grid) and 20 % outliers; the counting path must
  // select the same median slope as the listing path, to rounding.
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> grid(0, 200);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int n : {2, 3, 4, 5, 50, 301, 600}) {
    std::vector<double> x, y;
    for (int i = 0; i < n; ++i) {
      x.push_back(0.5 * grid(rng));
      y.push_back(-1.0 + 0.7 * x.back() + noise(rng) + (uniform(rng) < 0.2 ? 50.0 : 0.0));
    }
    if (x[0] == x[1] && n == 2) x[1] += 1.0;
    const LineFit listed = theil_sen_fit(x, y);
    const LineFit counted = theil_sen_fit(x, y, kByCounting);
    EXPECT_NEAR(counted.slope, listed.slope, 1e-12 * std::max(1.0, std::abs(listed.slope)))
        << "n = " << n;
    EXPECT_NEAR(counted.intercept, listed.intercept, 1e-9) << "n = " << n;
    const LineFit again = theil_sen_fit(x, y, kByCounting);
    EXPECT_EQ(again.slope, counted.slope);
    EXPECT_EQ(again.intercept, counted.intercept);
  }
}

TEST(TheilSen, MedianOfTheSlopesOddAndEven) {
  // (0,0) (1,1) (2,4): slopes 1, 4/2, 3 → median 2.
  // x = {0, 1, 2, 4}, y = {0, 1, 3, 7}: slopes 1, 3/2, 7/4, 2, 6/3, 4/2 → sorted
  // 1, 1.5, 1.75, 2, 2, 2 → an even count, median (1.75 + 2)/2 = 1.875.
  for (const TheilSenParams& params : {TheilSenParams{}, kByCounting}) {
    EXPECT_DOUBLE_EQ(theil_sen_fit(std::vector<double>{0.0, 1.0, 2.0},
                                   std::vector<double>{0.0, 1.0, 4.0}, params)
                         .slope,
                     2.0);
    EXPECT_DOUBLE_EQ(theil_sen_fit(std::vector<double>{0.0, 1.0, 2.0, 4.0},
                                   std::vector<double>{0.0, 1.0, 3.0, 7.0}, params)
                         .slope,
                     1.875);
  }
}

TEST(TheilSen, PairsWithEqualXHaveNoSlope) {
  // x = {0, 1, 1}, y = {0, 1, 100}: the vertical pair (1,2) has no slope and is skipped;
  // the others are 1 and 100, median 50.5.
  const std::vector<double> x = {0.0, 1.0, 1.0};
  const std::vector<double> y = {0.0, 1.0, 100.0};
  EXPECT_DOUBLE_EQ(theil_sen_fit(x, y).slope, 50.5);
  EXPECT_DOUBLE_EQ(theil_sen_fit(x, y, kByCounting).slope, 50.5);
}

TEST(TheilSen, LargeInputUsesTheCountingPath) {
  // 20,000 points: 2·10⁸ pairwise slopes would need 1.6 GB listed; counting needs a few MB.
  const DriftWithJump data = drift_with_jump(20000);
  const LineFit fit = theil_sen_fit(data.time_s, data.error_rad);
  EXPECT_NEAR(fit.slope, DriftWithJump::kSlope, 0.003);
}

TEST(LineFit, RejectsBadInput) {
  const std::vector<double> same_x = {1.0, 1.0, 1.0};
  const std::vector<double> y3 = {0.0, 1.0, 2.0};
  EXPECT_THROW(theil_sen_fit(same_x, y3), UsageError);
  EXPECT_THROW(theil_sen_fit(std::vector<double>{1.0}, std::vector<double>{1.0}), UsageError);
  EXPECT_THROW(theil_sen_fit(y3, std::vector<double>{1.0, 2.0}), UsageError);
  EXPECT_THROW(theil_sen_fit(y3, std::vector<double>{1.0, NAN, 2.0}), UsageError);
}

}  // namespace
}  // namespace omninav::measures
