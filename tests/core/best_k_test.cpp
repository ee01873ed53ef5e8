// BestK (best_k.hpp) against sorting everything and keeping the first k.
#include "omninav/core/best_k.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

namespace omninav {
namespace {

using Item = std::pair<int, int>;  // (value, index): smaller value better, ties by index

TEST(BestK, KeepsTheKBestInOrderWhateverTheOrderOfTheOffers) {
  const auto better = [](const Item& a, const Item& b) { return a < b; };
  std::mt19937 random(3);
  std::uniform_int_distribution<int> value(0, 9);  // many ties
  for (std::size_t n : {0u, 1u, 7u, 100u}) {
    std::vector<Item> items;
    for (std::size_t i = 0; i < n; ++i) items.emplace_back(value(random), static_cast<int>(i));
    std::shuffle(items.begin(), items.end(), random);
    std::vector<Item> sorted = items;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k : {0u, 1u, 5u, 100u, 150u}) {
      BestK<Item, decltype(better)> best(k, better);
      for (const Item& item : items) best.offer(item);
      const std::vector<Item> expected(
          sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(std::min(k, n)));
      EXPECT_EQ(std::move(best).take_sorted(), expected) << "n = " << n << ", k = " << k;
    }
  }
}

}  // namespace
}  // namespace omninav
