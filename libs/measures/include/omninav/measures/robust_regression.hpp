#pragma once
// Robust linear regression y = a + b·x, for the trend of the compass error: its slope against
// time (°/s) and against distance travelled (°/m), the last two columns of Tables 3 and 4 of
// Labrosse 2006.
//
// Which estimator: the paper says only "the slope of the robust linear regression of the
// error as a function of time and distance travelled" (§4, before Table 3) and does not name
// it. We chose Theil–Sen: the median of the slopes of all pairs of points, intercept the
// median of y − b·x. It has a 29.3 % breakdown point (more than a quarter of the points can
// be arbitrarily wrong, e.g. a jump of the compass, without moving the slope far), it needs
// no tuning constant or scale estimate (unlike Huber/bisquare M-estimators), it is exact on
// noiseless data and it is deterministic. Our slopes may therefore differ from the paper's
// in the last digits on the same data.

#include <cstddef>
#include <span>

namespace omninav::measures {

struct LineFit {
  double intercept = 0.0;  // a, in the unit of y
  double slope = 0.0;      // b, in the unit of y per unit of x (e.g. rad/s)

  double at(double x) const { return intercept + slope * x; }
};

struct TheilSenParams {
  // Up to this many points the pairwise slopes are listed and the median selected directly:
  // O(n²) time and n²/2 doubles of memory (36 MB at 3000 points). Above it the same median
  // is found by bisection over slope values, counting the pairs below each candidate slope
  // by merge-sort inversion counting: O(n log n) per step, at most 64 steps per order
  // statistic, little memory. Both give the same median up to rounding (the counting test
  // compares y − t·x, which rounds differently from the slope quotients for pairs whose
  // slopes are within a few ulps of each other). Deterministic either way, no subsampling.
  std::size_t max_exact_points = 3000;
};

// Theil–Sen fit. Pairs with equal x have no slope and are skipped. Throws UsageError if the
// sizes differ, a value is not finite, or all x are equal (no slope at all).
LineFit theil_sen_fit(std::span<const double> x, std::span<const double> y,
                      const TheilSenParams& params = {});

}  // namespace omninav::measures
