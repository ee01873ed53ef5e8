#include "omninav/measures/error_stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::measures {
namespace {

void require_finite(std::span<const double> values, const char* what) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw UsageError(std::string("error statistics: ") + what + " " + std::to_string(i) +
                       " is not finite");
    }
  }
}

}  // namespace

std::vector<double> angular_errors(std::span<const double> estimates_rad,
                                   std::span<const double> truths_rad) {
  if (estimates_rad.size() != truths_rad.size()) {
    throw UsageError("error statistics: " + std::to_string(estimates_rad.size()) +
                     " estimates but " + std::to_string(truths_rad.size()) + " truths");
  }
  require_finite(estimates_rad, "estimate");
  require_finite(truths_rad, "truth");
  std::vector<double> errors(estimates_rad.size());
  for (std::size_t i = 0; i < errors.size(); ++i) {
    errors[i] = signed_difference(estimates_rad[i], truths_rad[i]);
  }
  return errors;
}

ErrorStats angular_error_stats(std::span<const double> estimates_rad,
                               std::span<const double> truths_rad) {
  return error_stats(angular_errors(estimates_rad, truths_rad));
}

ErrorStats error_stats(std::span<const double> errors) {
  if (errors.empty()) throw UsageError("error statistics: no errors given");
  require_finite(errors, "error");
  ErrorStats stats;
  stats.count = errors.size();
  const double n = static_cast<double>(errors.size());
  double sum = 0.0;
  double sum_squares = 0.0;
  for (double e : errors) {
    sum += e;
    sum_squares += e * e;
    stats.max_abs = std::max(stats.max_abs, std::abs(e));
  }
  stats.mean = sum / n;
  stats.rms = std::sqrt(sum_squares / n);
  // Two passes: the spread about the mean, not E[e²] − mean², which cancels badly when the
  // bias is large compared with the spread.
  if (errors.size() < 2) {
    stats.stddev = std::numeric_limits<double>::quiet_NaN();
  } else {
    double sum_deviations = 0.0;
    for (double e : errors) sum_deviations += (e - stats.mean) * (e - stats.mean);
    stats.stddev = std::sqrt(sum_deviations / (n - 1.0));
  }
  return stats;
}

ErrorStats in_degrees(const ErrorStats& stats_rad) {
  ErrorStats stats = stats_rad;
  stats.max_abs = rad_to_deg(stats_rad.max_abs);
  stats.mean = rad_to_deg(stats_rad.mean);
  stats.stddev = rad_to_deg(stats_rad.stddev);
  stats.rms = rad_to_deg(stats_rad.rms);
  return stats;
}

}  // namespace omninav::measures
