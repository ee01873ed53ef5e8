#include "omninav/lattice/similar_places.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <random>

#include "omninav/core/statistics.hpp"
#include "omninav/signature/dissimilarity.hpp"

namespace omninav::lattice {
namespace {

// A map of `count` places whose signatures (3 lines of 15 components, the last lines' layout in
// float) hold magnitude(i, v) at value v of place i.
template <typename Magnitude>
memory::VisualMemory map_of(int count, const memory::MapParameters& parameters,
                            Magnitude magnitude) {
  memory::VisualMemory map(parameters);
  for (int i = 0; i < count; ++i) {
    memory::Place place;
    signature::Signature& s = place.signature;
    s.rows = 3;
    s.components = parameters.signature.components;
    s.width_px = 64;
    s.magnitude.resize(s.size());
    s.phase_rad.assign(s.size(), 0.0F);
    for (std::size_t v = 0; v < s.magnitude.size(); ++v) s.magnitude[v] = magnitude(i, v);
    map.add_place(std::move(place));
  }
  return map;
}

// Random signatures and Eq. 6 weights, so that folding the weights in is checked too.
memory::VisualMemory random_map(int count, unsigned seed) {
  memory::MapParameters parameters;
  parameters.weights.alpha = {1.0, 0.5, 2.0};
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> magnitude(0.0F, 40.0F);
  return map_of(count, parameters, [&](int, std::size_t) { return magnitude(random); });
}

TEST(PlaceDissimilarities, IsEquation6) {
  const memory::VisualMemory map = random_map(5, 1);
  const PlaceDissimilarities dissimilarity(map);
  for (int a = 0; a < 5; ++a) {
    for (int b = 0; b < 5; ++b) {
      const double expected = signature::dissimilarity(
          map.place(a).signature, map.place(b).signature, -1, map.parameters().weights);
      // Summed in floats: a relative error of a few 1e-7.
      EXPECT_NEAR(dissimilarity(a, b), expected, 1e-5 * expected) << a << ", " << b;
    }
  }
}

TEST(PlaceDissimilarities, MostSimilarIsWhatRankingEveryPairGives) {
  // More places than one block of the search (64), and a last block that is not full.
  const memory::VisualMemory map = random_map(150, 2);
  const PlaceDissimilarities dissimilarity(map);
  const int count = 24;
  const std::vector<std::vector<SimilarPlace>> similar = dissimilarity.most_similar(count);
  ASSERT_EQ(similar.size(), 150u);
  for (int a = 0; a < 150; ++a) {
    std::vector<int> others;
    for (int b = 0; b < 150; ++b) {
      if (b != a) others.push_back(b);
    }
    std::sort(others.begin(), others.end(), [&](int x, int y) {
      return std::make_pair(dissimilarity(a, x), x) < std::make_pair(dissimilarity(a, y), y);
    });
    ASSERT_EQ(similar[a].size(), static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) {
      EXPECT_EQ(similar[a][i].place, others[i]) << "place " << a << ", rank " << i;
      EXPECT_DOUBLE_EQ(similar[a][i].dissimilarity, dissimilarity(a, others[i]));
    }
  }
}

// A map whose places' signatures change smoothly along a path, as a driven stream's do: place
// i's nearest places by Eq. 6 are those beside it along the path.
memory::VisualMemory path_map(int count) {
  return map_of(count, memory::MapParameters{}, [](int i, std::size_t v) {
    return static_cast<float>(
        20.0 + 10.0 * std::sin(0.37 * static_cast<double>(v) + 0.02 * static_cast<double>(i)));
  });
}

TEST(PlaceDissimilarities, TheIndexFindsTheNearestPlacesAlongAPathWithoutComparingEveryPair) {
  const memory::VisualMemory map = path_map(600);
  const PlaceDissimilarities dissimilarity(map);
  const int count = 4;
  const std::vector<std::vector<SimilarPlace>> exact = dissimilarity.most_similar(count);
  cv::theRNG() = cv::RNG(7);
  const std::vector<std::vector<SimilarPlace>> indexed = dissimilarity.most_similar_indexed(count);
  // The caller's random generator is left as it was.
  EXPECT_EQ(cv::theRNG().next(), cv::RNG(7).next());
  ASSERT_EQ(indexed.size(), exact.size());
  std::size_t found = 0;
  for (std::size_t a = 0; a < exact.size(); ++a) {
    ASSERT_EQ(indexed[a].size(), static_cast<std::size_t>(count)) << a;
    for (std::size_t rank = 0; rank < indexed[a].size(); ++rank) {
      const SimilarPlace& place = indexed[a][rank];
      EXPECT_NE(place.place, static_cast<int>(a));
      EXPECT_DOUBLE_EQ(place.dissimilarity, dissimilarity(static_cast<int>(a), place.place));
      if (rank > 0) {
        EXPECT_GE(place.dissimilarity, indexed[a][rank - 1].dissimilarity);
      }
    }
    for (const SimilarPlace& truth : exact[a]) {
      for (const SimilarPlace& place : indexed[a]) found += place.place == truth.place ? 1 : 0;
    }
  }
  // An approximate search, but on a path it misses few of the nearest places.
  EXPECT_GT(static_cast<double>(found) / static_cast<double>(exact.size() * count), 0.95);
  // The same lists for the same map.
  const std::vector<std::vector<SimilarPlace>> again = dissimilarity.most_similar_indexed(count);
  for (std::size_t a = 0; a < exact.size(); ++a) {
    for (std::size_t rank = 0; rank < again[a].size(); ++rank) {
      EXPECT_EQ(again[a][rank].place, indexed[a][rank].place);
    }
  }
}

TEST(PlaceDissimilarities, FewerPlacesThanAsked) {
  const memory::VisualMemory map = random_map(3, 3);
  const std::vector<std::vector<SimilarPlace>> similar = PlaceDissimilarities(map).most_similar(24);
  for (const std::vector<SimilarPlace>& list : similar) EXPECT_EQ(list.size(), 2u);
  const std::vector<std::vector<SimilarPlace>> indexed =
      PlaceDissimilarities(map).most_similar_indexed(24);
  for (const std::vector<SimilarPlace>& list : indexed) EXPECT_EQ(list.size(), 2u);
}

TEST(PlaceDissimilarities, PairQuantileOverAllPairsOrAnEvenSample) {
  const memory::VisualMemory map = random_map(120, 4);
  const PlaceDissimilarities dissimilarity(map);
  std::vector<double> all;
  for (int a = 0; a < 120; ++a) {
    for (int b = a + 1; b < 120; ++b) all.push_back(dissimilarity(a, b));
  }
  // 7,140 pairs: every one of them when allowed.
  EXPECT_EQ(dissimilarity.pair_quantile(0.9, all.size()), quantile(all, 0.9));
  // A sample of about 1,200 pairs: its 90th percentile lies between the 85th and the 95th of
  // all pairs (the rank's standard error is under 1 %).
  const double sampled = dissimilarity.pair_quantile(0.9, 1200);
  EXPECT_GT(sampled, quantile(all, 0.85));
  EXPECT_LT(sampled, quantile(all, 0.95));
}

}  // namespace
}  // namespace omninav::lattice
