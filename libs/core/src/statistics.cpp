#include "omninav/core/statistics.hpp"

#include <algorithm>
#include <cstddef>

namespace omninav {

double quantile(std::vector<double> values, double share) {
  const std::size_t index = std::min(
      values.size() - 1, static_cast<std::size_t>(share * static_cast<double>(values.size())));
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(index);
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

double median_of_middles(std::vector<double> values) {
  const std::size_t half = values.size() / 2;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(half);
  std::nth_element(values.begin(), middle, values.end());
  const double upper = *middle;
  if (values.size() % 2 == 1) return upper;
  const double lower = *std::max_element(values.begin(), middle);
  return 0.5 * (lower + upper);
}

double pair_quantile(std::size_t count, double share, std::size_t max_pairs,
                     const std::function<double(std::size_t, std::size_t)>& value) {
  const std::size_t pairs = count * (count - 1) / 2;
  std::vector<double> values;
  if (pairs <= max_pairs) {
    values.reserve(pairs);
    for (std::size_t a = 0; a < count; ++a) {
      for (std::size_t b = a + 1; b < count; ++b) values.push_back(value(a, b));
    }
  } else {
    const std::size_t half = count / 2;
    const std::size_t offsets = std::clamp<std::size_t>(max_pairs / count, 1, half);
    values.reserve(offsets * count);
    for (std::size_t a = 0; a < count; ++a) {
      for (std::size_t j = 0; j < offsets; ++j)
        values.push_back(value(a, (a + 1 + j * half / offsets) % count));
    }
  }
  return quantile(std::move(values), share);
}

}  // namespace omninav
