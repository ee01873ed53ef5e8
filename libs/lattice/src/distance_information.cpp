#include "distance_information.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace omninav::lattice::detail {
namespace {

// Ranks from 1, ties given their mean rank.
std::vector<double> ranks(const std::vector<double>& values) {
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  std::vector<double> result(values.size());
  for (std::size_t first = 0; first < order.size();) {
    std::size_t last = first;
    while (last + 1 < order.size() && values[order[last + 1]] == values[order[first]]) ++last;
    const double mean_rank = 0.5 * static_cast<double>(first + last) + 1.0;
    for (std::size_t i = first; i <= last; ++i) result[order[i]] = mean_rank;
    first = last + 1;
  }
  return result;
}

double pearson(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  const double mean_x = std::accumulate(x.begin(), x.end(), 0.0) / n;
  const double mean_y = std::accumulate(y.begin(), y.end(), 0.0) / n;
  double xy = 0.0, xx = 0.0, yy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    xy += (x[i] - mean_x) * (y[i] - mean_y);
    xx += (x[i] - mean_x) * (x[i] - mean_x);
    yy += (y[i] - mean_y) * (y[i] - mean_y);
  }
  return xx > 0.0 && yy > 0.0 ? xy / std::sqrt(xx * yy) : 0.0;
}

}  // namespace

std::optional<double> dissimilarity_gap_correlation(const memory::VisualMemory& memory,
                                                    const PlaceDissimilarities& dissimilarity,
                                                    int max_gap) {
  const int count = static_cast<int>(memory.place_count());
  std::vector<bool> linked_to_next(count, false);  // place i and i + 1 are consecutive
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
    const std::size_t first = std::min(edge.from, edge.to);
    if (std::max(edge.from, edge.to) == first + 1) linked_to_next[first] = true;
  }
  std::vector<double> gaps, values;
  for (int place = 0; place < count; ++place) {
    for (int gap = 1; gap <= max_gap && place + gap < count; ++gap) {
      if (!linked_to_next[place + gap - 1]) break;
      gaps.push_back(gap);
      values.push_back(dissimilarity(place, place + gap));
    }
  }
  if (gaps.size() < 8 || *std::max_element(gaps.begin(), gaps.end()) < 2) return std::nullopt;
  return pearson(ranks(gaps), ranks(values));
}

}  // namespace omninav::lattice::detail
