#include "omninav/measures/robust_regression.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "omninav/core/errors.hpp"
#include "omninav/core/statistics.hpp"

namespace omninav::measures {
namespace {

void require_line_data(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size()) {
    throw UsageError("line fit: " + std::to_string(x.size()) + " x values but " +
                     std::to_string(y.size()) + " y values");
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      throw UsageError("line fit: point " + std::to_string(i) + " is not finite");
    }
  }
  const auto [min_x, max_x] = std::minmax_element(x.begin(), x.end());
  if (x.size() < 2 || *min_x == *max_x) {
    throw UsageError("line fit: needs at least two distinct x values (got " +
                     std::to_string(x.size()) + " points)");
  }
}

double median_slope_exact(std::span<const double> x, std::span<const double> y) {
  std::vector<double> slopes;
  slopes.reserve(x.size() * (x.size() - 1) / 2);
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t j = i + 1; j < x.size(); ++j) {
      if (x[i] != x[j]) slopes.push_back((y[j] - y[i]) / (x[j] - x[i]));
    }
  }
  return median_of_middles(std::move(slopes));
}

// A bijection between doubles and int64 that preserves order (−0 and +0 both map to 0), so
// that bisecting over keys visits every representable slope between the bounds.
std::int64_t order_key(double value) {
  const auto bits = std::bit_cast<std::int64_t>(value);
  return bits >= 0 ? bits : std::numeric_limits<std::int64_t>::min() - bits;
}

double from_order_key(std::int64_t key) {
  return std::bit_cast<double>(key >= 0 ? key : std::numeric_limits<std::int64_t>::min() - key);
}

// Order statistics of the pairwise slopes without listing them. With the points sorted by x,
// a pair i < j (x_i < x_j) has slope ≤ t exactly when y_j − t·x_j ≤ y_i − t·x_i, so the number
// of slopes ≤ t is the number of non-ascending pairs of z = y − t·x, counted by merge sort.
class SlopeSelector {
 public:
  SlopeSelector(std::span<const double> x, std::span<const double> y) {
    std::vector<std::size_t> order(x.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    // Equal x by decreasing y: z then never ascends inside a group of equal x (the same t·x
    // is subtracted from each y, and rounding is monotone), so those pairs, which have no
    // slope, are all counted as non-ascending and removed as one constant below.
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return x[a] != x[b] ? x[a] < x[b] : y[a] > y[b];
    });
    for (std::size_t i : order) {
      x_.push_back(x[i]);
      y_.push_back(y[i]);
    }
    const auto n = static_cast<std::uint64_t>(x_.size());
    all_pairs_ = n * (n - 1) / 2;
    std::uint64_t group = 1;
    double min_gap = std::numeric_limits<double>::infinity();
    for (std::size_t i = 1; i <= x_.size(); ++i) {
      if (i < x_.size() && x_[i] == x_[i - 1]) {
        ++group;
        continue;
      }
      equal_x_pairs_ += group * (group - 1) / 2;
      group = 1;
      if (i < x_.size()) min_gap = std::min(min_gap, x_[i] - x_[i - 1]);
    }
    const auto [min_y, max_y] = std::minmax_element(y_.begin(), y_.end());
    // No slope is steeper than the whole range of y over the smallest step in x.
    slope_bound_ = (*max_y - *min_y) / min_gap;
    const double max_abs_x = std::max(std::abs(x_.front()), std::abs(x_.back()));
    const double max_abs_y = std::max(std::abs(*min_y), std::abs(*max_y));
    if (!std::isfinite(slope_bound_ * max_abs_x + max_abs_y)) {
      throw UsageError("Theil-Sen fit: slopes too steep to evaluate in double precision");
    }
    z_.resize(x_.size());
    buffer_.resize(x_.size());
  }

  std::uint64_t slope_count() const { return all_pairs_ - equal_x_pairs_; }

  // The k-th smallest slope, k from 1 to slope_count().
  double kth(std::uint64_t k) {
    std::int64_t low = order_key(-slope_bound_);
    std::int64_t high = order_key(slope_bound_);
    while (low < high) {
      const std::int64_t mid =
          low + static_cast<std::int64_t>(
                    (static_cast<std::uint64_t>(high) - static_cast<std::uint64_t>(low)) / 2);
      if (count_at_most(from_order_key(mid)) >= k) {
        high = mid;
      } else {
        low = mid + 1;
      }
    }
    return from_order_key(low);
  }

 private:
  // Number of slopes ≤ t.
  std::uint64_t count_at_most(double t) {
    for (std::size_t i = 0; i < x_.size(); ++i) z_[i] = y_[i] - t * x_[i];
    return all_pairs_ - ascending_pairs() - equal_x_pairs_;
  }

  // Pairs i < j with z_i < z_j, by bottom-up merge sort of z_ (which it sorts).
  std::uint64_t ascending_pairs() {
    const std::size_t n = z_.size();
    std::uint64_t count = 0;
    for (std::size_t width = 1; width < n; width *= 2) {
      for (std::size_t low = 0; low < n; low += 2 * width) {
        const std::size_t mid = std::min(low + width, n);
        const std::size_t high = std::min(low + 2 * width, n);
        std::size_t i = low, j = mid, out = low;
        // For each element of the right run, the left elements already taken are exactly
        // those smaller than it.
        while (i < mid && j < high) {
          if (z_[i] < z_[j]) {
            buffer_[out++] = z_[i++];
          } else {
            count += i - low;
            buffer_[out++] = z_[j++];
          }
        }
        while (i < mid) buffer_[out++] = z_[i++];
        while (j < high) {
          count += i - low;
          buffer_[out++] = z_[j++];
        }
      }
      z_.swap(buffer_);
    }
    return count;
  }

  std::vector<double> x_, y_, z_, buffer_;
  std::uint64_t all_pairs_ = 0;
  std::uint64_t equal_x_pairs_ = 0;
  double slope_bound_ = 0.0;
};

double median_slope_by_counting(std::span<const double> x, std::span<const double> y) {
  SlopeSelector selector(x, y);
  const std::uint64_t count = selector.slope_count();
  const double upper = selector.kth(count / 2 + 1);
  if (count % 2 == 1) return upper;
  return 0.5 * (selector.kth(count / 2) + upper);
}

}  // namespace

LineFit theil_sen_fit(std::span<const double> x, std::span<const double> y,
                      const TheilSenParams& params) {
  require_line_data(x, y);
  LineFit fit;
  fit.slope = x.size() <= params.max_exact_points ? median_slope_exact(x, y)
                                                  : median_slope_by_counting(x, y);
  std::vector<double> intercepts(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) intercepts[i] = y[i] - fit.slope * x[i];
  fit.intercept = median_of_middles(std::move(intercepts));
  return fit;
}

}  // namespace omninav::measures
