#include "omninav/signature/plateau.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "omninav/core/statistics.hpp"

namespace omninav::signature {
namespace {

// A one-line, one-component signature of magnitude `value`: two of them differ by |a − b| per
// value, so every pair's dissimilarity is known.
Signature scalar(double value) {
  Signature s;
  s.rows = 1;
  s.components = 1;
  s.width_px = 4;
  s.magnitude = {static_cast<float>(value)};
  s.phase_rad = {0.0f};
  return s;
}

// The 90th percentile of |i − j| over pairs of the given indices, as core/statistics ranks.
double expected(const std::vector<int>& indices) {
  std::vector<double> pairs;
  for (std::size_t a = 0; a < indices.size(); ++a) {
    for (std::size_t b = a + 1; b < indices.size(); ++b) {
      pairs.push_back(std::abs(indices[a] - indices[b]));
    }
  }
  return quantile(pairs, kPlateauQuantile);
}

TEST(PlateauEstimate, TheQuantileOfAllPairsWhileTheSamplesFit) {
  PlateauEstimate plateau({}, 16);
  EXPECT_FALSE(plateau.per_value());
  plateau.add(scalar(0.0));
  EXPECT_FALSE(plateau.per_value()) << "one sample, no pair";
  std::vector<int> seen = {0};
  for (int i = 1; i < 16; ++i) {
    plateau.add(scalar(i));
    seen.push_back(i);
    ASSERT_TRUE(plateau.per_value());
    EXPECT_DOUBLE_EQ(*plateau.per_value(), expected(seen)) << i;
  }
}

TEST(PlateauEstimate, KeepsSamplesEvenlySpreadOverALongStream) {
  // 100 signatures through 16 samples: the stride doubles to 8, the samples are 0, 8, ..., 96.
  PlateauEstimate plateau({}, 16);
  for (int i = 0; i < 100; ++i) plateau.add(scalar(i));
  EXPECT_EQ(plateau.signatures_seen(), 100u);
  EXPECT_EQ(plateau.samples(), 13u);
  std::vector<int> kept;
  for (int i = 0; i < 100; i += 8) kept.push_back(i);
  EXPECT_DOUBLE_EQ(*plateau.per_value(), expected(kept));
  // The same pairs' quantile as the lattice's, which pairs a map's places (core/statistics.hpp).
  EXPECT_DOUBLE_EQ(*plateau.per_value(), pair_quantile(kept.size(), kPlateauQuantile, 1000,
                                                       [&](std::size_t a, std::size_t b) {
                                                         return std::abs(kept[a] - kept[b]) * 1.0;
                                                       }));
}

TEST(PlateauEstimate, TheFloorIsTheLowTenthOfTheSampledTurnsOnTheSpot) {
  // Steps of 1, 2, ..., 31 between consecutive frames, each a turn on the spot but every third;
  // 16 samples hold the first 16 frames, then every other one of 32 (frames 0, 2, ..., 30).
  PlateauEstimate plateau({}, 16);
  EXPECT_FALSE(plateau.floor_per_value());
  double at = 0.0;
  std::vector<double> turns_sampled;
  for (int i = 0; i < 32; ++i) {
    const bool turn = i % 3 != 0;
    const bool sampled = plateau.will_sample();
    EXPECT_EQ(sampled, i < 16 || i % 2 == 0) << i;
    at += i;  // the step from frame i − 1 is i
    plateau.add_frame(scalar(at), turn);
    if (i > 0 && turn && (i % 2 == 0)) turns_sampled.push_back(i);
  }
  ASSERT_TRUE(plateau.floor_per_value());
  EXPECT_DOUBLE_EQ(*plateau.floor_per_value(), quantile(turns_sampled, kFloorQuantile));
  // A map's place (add) brings no step of its own; it fills the samples, which are halved again
  // (frames 0, 4, ..., 28 and the place): the floor is that of the turns still held.
  plateau.add(scalar(1000.0));
  EXPECT_DOUBLE_EQ(*plateau.floor_per_value(),
                   quantile(std::vector<double>{4, 8, 16, 20, 28}, kFloorQuantile));
}

}  // namespace
}  // namespace omninav::signature
