#pragma once
// Order statistics of a sample, one implementation for the whole project (medians of
// spacings, ratios, errors; the lattice's plateau quantile; Theil-Sen's slopes). Two medians,
// named for how they treat an even count: median() takes the upper middle value (a value of
// the sample), median_of_middles() the mean of the two middle values (the textbook median).

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

namespace omninav {

// The value at rank ⌊share·n⌋ (clamped to the last) of the n `values`, by std::nth_element:
// share 0.5 is the median, the upper of the two middle values when n is even. `values` must
// not be empty.
double quantile(std::vector<double> values, double share);

inline double median(std::vector<double> values) {
  return quantile(std::move(values), 0.5);
}

// The median with an even count's two middle values averaged (Theil-Sen's estimator, as
// published). `values` must not be empty.
double median_of_middles(std::vector<double> values);

// The `share` quantile (as quantile()) of value(a, b) over the pairs a < b of `count` items (at
// least two): over all pairs when there are at most `max_pairs`, else over about `max_pairs`,
// every item paired with the items at evenly spaced index offsets over 1..count/2 (pairs near
// and far in the listing alike): the same for the same items. The plateau of the dissimilarity
// (signature/plateau.hpp) over a map's places or a stream's frames.
double pair_quantile(std::size_t count, double share, std::size_t max_pairs,
                     const std::function<double(std::size_t, std::size_t)>& value);

}  // namespace omninav
