#include "omninav/signature/hierarchy.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <set>

#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "rendered_room.hpp"
#include "synthetic_signatures.hpp"

namespace omninav::signature {
namespace {

TEST(Hierarchy, LevelDissimilaritiesAreEquationTwoAndSix) {
  SignatureExtractor extractor({15, ColourMode::kPerChannel});
  std::vector<Signature> places;
  for (double x : {1.0, 1.6, 2.2, 3.4})
    places.push_back(extractor.compute(testing::render(x, 2.0, 0)));
  const Signature query = extractor.compute(testing::render(1.9, 2.2, 70.0));
  for (const ComponentWeights& weights :
       {ComponentWeights{}, parse_component_weights("0, 1, 2, 0.5", "test")}) {
    SignatureIndex index(45, 3, {2, 5, 15}, weights);
    for (const Signature& s : places) index.add(s);
    for (std::size_t level = 0; level < 3; ++level) {
      const int m = index.levels()[level];
      const Eigen::VectorXf dis = index.dissimilarities(query, level);
      for (std::size_t i = 0; i < places.size(); ++i) {
        const double expected = dissimilarity(query, places[i], m, weights);
        EXPECT_NEAR(dis[static_cast<Eigen::Index>(i)], expected, 1e-4 * expected)
            << "level " << level << ", place " << i;
      }
    }
  }
}

TEST(Hierarchy, PrunedSearchFindsTheExhaustiveBestAndNestsItsCandidates) {
  // 2,000 synthetic places on a 30 m floor every 0.55 m, 300 noisy queries between them.
  const testing::SyntheticPlaces field(30.0, 45, 1, 15, 3);
  SignatureIndex index(45, 1, {2, 5, 15});
  std::vector<std::pair<double, double>> positions;
  for (double x = 0.0; x < 30.0; x += 0.55) {
    for (double y = 0.0; y < 30.0 && positions.size() < 2000; y += 0.55) {
      positions.emplace_back(x, y);
      index.add(field.at(x, y));
    }
  }
  std::mt19937 random(4);
  std::uniform_real_distribution<double> coordinate(0.0, 0.55 * (2000 / 55) - 0.55);
  int same = 0, queries = 300;
  for (int q = 0; q < queries; ++q) {
    const Signature query = field.at(coordinate(random), coordinate(random), &random, 1.0);
    const SearchResult pruned = index.search(query, 800.0, 5);
    const SearchResult exhaustive = index.search_exhaustive(query, 800.0, 5);
    ASSERT_EQ(pruned.best.size(), 5u);  // top_k places, however few candidates
    same += pruned.best.front().place == exhaustive.best.front().place;
    // The first level compares every place, later ones only the previous candidates.
    EXPECT_EQ(pruned.levels[0].evaluated, index.size());
    for (std::size_t l = 1; l < pruned.levels.size(); ++l) {
      // The previous candidates, and the previous best 5 when the candidates are fewer.
      EXPECT_GE(pruned.levels[l].evaluated, pruned.levels[l - 1].candidates.size());
      EXPECT_LE(pruned.levels[l].evaluated, pruned.levels[l - 1].candidates.size() + 5);
      EXPECT_GE(pruned.levels[l].evaluated, 5u);
      std::set<std::uint32_t> previous;
      for (const Candidate& c : pruned.levels[l - 1].candidates) previous.insert(c.place);
      for (const Candidate& c : pruned.levels[l].candidates) {
        EXPECT_TRUE(previous.count(c.place)) << "level " << l;
      }
    }
    // Candidates come best first; the best scores 1000.
    const auto& finest = pruned.levels.back().candidates;
    ASSERT_FALSE(finest.empty());
    EXPECT_FLOAT_EQ(finest.front().similarity, 1000.0f);
    EXPECT_TRUE(std::is_sorted(
        finest.begin(), finest.end(),
        [](const Candidate& a, const Candidate& b) { return a.dissimilarity < b.dissimilarity; }));
  }
  // Issue §3: the pruned best equals the exhaustive finest-level best in ≥ 99% of queries.
  std::cout << "pruned best = exhaustive best in " << same << " of " << queries << " queries\n";
  EXPECT_GE(same, 0.99 * queries);
}

TEST(Hierarchy, ExhaustiveLevelsRescaleOverEveryPlace) {
  const testing::SyntheticPlaces field(10.0, 4, 1, 6, 1);
  SignatureIndex index(4, 1, {2, 6});
  for (int i = 0; i < 40; ++i) index.add(field.at(0.25 * i, 1.0));
  const SearchResult r = index.search_exhaustive(field.at(3.0, 1.0), 0.0, 40);
  for (const LevelResult& level : r.levels) {
    EXPECT_EQ(level.candidates.size(), 40u);  // threshold 0: every place
    EXPECT_FLOAT_EQ(level.candidates.front().similarity, 1000.0f);
    EXPECT_FLOAT_EQ(level.candidates.back().similarity, 0.0f);
  }
  EXPECT_EQ(r.best.size(), 40u);
  EXPECT_EQ(r.best.front().place, 12u);  // 3.0 m is place 12 exactly
}

TEST(Hierarchy, EmptyIndexAndBadInput) {
  SignatureIndex index(45, 1, {2, 5, 15});
  const Signature query = compute_signature(testing::render(2, 2, 0), {15, ColourMode::kLuminance});
  const SearchResult empty = index.search(query, 800.0, 3);
  EXPECT_TRUE(empty.best.empty());
  EXPECT_EQ(empty.levels.size(), 3u);
  const Signature colour =
      compute_signature(testing::render(2, 2, 0), {15, ColourMode::kPerChannel});
  EXPECT_THROW(index.add(colour), UsageError);
  EXPECT_THROW(index.search(colour, 800.0, 3), UsageError);
  EXPECT_THROW(index.add(query.truncated(5)), UsageError);
  EXPECT_THROW(SignatureIndex(45, 1, {5, 2}), UsageError);
  EXPECT_THROW(SignatureIndex(45, 1, {}), UsageError);
}

TEST(Hierarchy, LevelsParseAndLoadFromConfig) {
  EXPECT_EQ(parse_levels("2, 5,15", "x"), (std::vector<int>{2, 5, 15}));
  EXPECT_THROW(parse_levels("5,2", "x"), UsageError);
  EXPECT_THROW(parse_levels("0,2", "x"), UsageError);
  EXPECT_THROW(parse_levels("two", "x"), UsageError);
  const ConfigReader config = ConfigReader::from_string(
      "localisation: {levels: '3,9', candidate_similarity: 700, max_probes: 4}", "memory.yaml");
  HierarchyParams params;
  load_hierarchy_params(config.section("localisation"), params);
  EXPECT_EQ(params.levels, (std::vector<int>{3, 9}));
  EXPECT_EQ(params.candidate_similarity, 700.0);
  EXPECT_EQ(params.max_probes, 4);
  const ConfigReader bad =
      ConfigReader::from_string("localisation: {levels: '9,3'}", "memory.yaml");
  try {
    load_hierarchy_params(bad.section("localisation"), params);
    FAIL();
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("memory.yaml"), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("levels"), std::string::npos);
  }
}

}  // namespace
}  // namespace omninav::signature
