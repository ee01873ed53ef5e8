#pragma once
// Order statistics of a sample, one implementation for the whole project (medians of
// spacings, ratios, errors; the lattice's plateau quantile).

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

}  // namespace omninav
