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

}  // namespace omninav
