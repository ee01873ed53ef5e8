#pragma once
// Error statistics for evaluation tables (docs/design.md, Evaluation): the count, max |e|, mean,
// standard deviation and RMS of a set of errors, as in the "Max.", "Mean" and "Std. dev."
// columns of Tables 3 and 4 of Labrosse 2006.
//
// Angular errors are e = wrap(estimate − truth) to (−π, π] (omninav::signed_difference), so an
// estimate of 179° against a truth of −179° is an error of −2°, never 358°.

#include <cstddef>
#include <span>
#include <vector>

namespace omninav::measures {

struct ErrorStats {
  std::size_t count = 0;  // number of errors
  double max_abs = 0.0;   // max |e|
  double mean = 0.0;      // signed mean: a bias shows here
  double stddev = 0.0;    // sample standard deviation (divides by n − 1); NaN when count < 2
  double rms = 0.0;       // sqrt(mean of e²): bias and spread together
};

// The per-sample angular errors wrap(estimates[i] − truths[i]) in (−π, π], radians.
// Throws UsageError if the sizes differ or a value is not finite (naming its index).
std::vector<double> angular_errors(std::span<const double> estimates_rad,
                                   std::span<const double> truths_rad);

// Statistics of angular errors (radians in, radians out): error_stats(angular_errors(...)).
ErrorStats angular_error_stats(std::span<const double> estimates_rad,
                               std::span<const double> truths_rad);

// Statistics of plain errors (any unit, e.g. metres; the result is in the same unit). The
// errors are used as given, with no wrapping. Throws UsageError if `errors` is empty or holds a
// value that is not finite.
ErrorStats error_stats(std::span<const double> errors);

// The same statistics converted from radians to degrees, for tables and CSV (degrees at the
// edges, docs/design.md Conventions).
ErrorStats in_degrees(const ErrorStats& stats_rad);

}  // namespace omninav::measures
