#include "omninav/core/statistics.hpp"

#include <gtest/gtest.h>

namespace omninav {
namespace {

TEST(Statistics, MedianTakesTheUpperMiddleValueOfAnEvenCount) {
  EXPECT_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 3.0);
  EXPECT_EQ(median({5.0}), 5.0);
}

TEST(Statistics, MedianOfMiddlesAveragesTheTwoMiddleValues) {
  EXPECT_EQ(median_of_middles({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(median_of_middles({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_EQ(median_of_middles({10.0, -10.0}), 0.0);
  EXPECT_EQ(median_of_middles({7.0}), 7.0);
}

TEST(Statistics, QuantileIsTheValueAtRankShareTimesCount) {
  const std::vector<double> values{50.0, 10.0, 40.0, 20.0, 30.0};
  EXPECT_EQ(quantile(values, 0.0), 10.0);
  EXPECT_EQ(quantile(values, 0.2), 20.0);  // rank 1
  EXPECT_EQ(quantile(values, 0.99), 50.0);
  EXPECT_EQ(quantile(values, 1.0), 50.0) << "clamped to the last";
}

}  // namespace
}  // namespace omninav
