#include "omninav/memory/localisation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

#include "grid_fixture.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::memory {
namespace {

using testing::kSpacing_m;

double distance_m(const CameraPose& a, const CameraPose& b) {
  return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m);
}

struct GridScores {
  int queries = 0;
  int within_spacing = 0;                   // finest best place within one spacing of the truth
  std::vector<int> level_contains_nearest;  // per level
  std::vector<double> level_mean_size;
  int pruned_equals_exhaustive = 0;
  std::vector<double> heading_errors_deg;  // query heading from the best place's, vs truth
  // Position errors against the truth, metres: the best place's, and the estimate between places.
  std::vector<double> place_errors_m, between_errors_m;
};

GridScores score(signature::ColourMode colour, std::size_t query_count) {
  const VisualMemory memory = testing::grid_memory(colour);
  const Localiser localiser(memory, {});
  const std::vector<testing::Query> queries = testing::random_queries(query_count);
  signature::SignatureExtractor extractor(memory.parameters().signature);
  GridScores s;
  s.level_contains_nearest.assign(localiser.params().hierarchy.levels.size(), 0);
  s.level_mean_size.assign(localiser.params().hierarchy.levels.size(), 0.0);
  for (const testing::Query& q : queries) {
    const signature::Signature signature = extractor.compute(q.frame.image);
    const Localisation pruned = localiser.localise(signature);
    const Localisation exhaustive = localiser.localise_exhaustive(signature);
    ++s.queries;
    const PlaceMatch& best = pruned.best.front();
    if (distance_m(*memory.place(best.place).truth, *q.frame.truth) <= kSpacing_m) {
      ++s.within_spacing;
    }
    if (best.place == exhaustive.best.front().place) ++s.pruned_equals_exhaustive;
    EXPECT_TRUE(pruned.position.has_value());
    if (pruned.position) {
      const Eigen::Vector2d truth = q.frame.truth->floor_position();
      s.place_errors_m.push_back((pruned.position->position - truth).norm());
      s.between_errors_m.push_back((pruned.position->between_places - truth).norm());
    }
    for (std::size_t l = 0; l < pruned.search.levels.size(); ++l) {
      const auto& candidates = pruned.search.levels[l].candidates;
      s.level_mean_size[l] += static_cast<double>(candidates.size()) / queries.size();
      if (std::any_of(candidates.begin(), candidates.end(),
                      [&](const signature::Candidate& c) { return c.place == q.nearest_place; })) {
        ++s.level_contains_nearest[l];
      }
    }
    EXPECT_TRUE(best.heading_rad.has_value());
    if (!best.heading_rad) continue;
    s.heading_errors_deg.push_back(std::fabs(signed_difference_deg(
        rad_to_deg(*best.heading_rad), rad_to_deg(q.frame.truth->heading_rad))));
  }
  std::sort(s.heading_errors_deg.begin(), s.heading_errors_deg.end());
  std::cout << signature::to_string(colour) << ": " << s.within_spacing << "/" << s.queries
            << " within one spacing; pruned = exhaustive " << s.pruned_equals_exhaustive
            << "; median heading error " << s.heading_errors_deg[s.queries / 2]
            << " deg; median position error " << median(s.place_errors_m)
            << " m at the best place, " << median(s.between_errors_m) << " m between places\n";
  for (std::size_t l = 0; l < s.level_mean_size.size(); ++l) {
    std::cout << "  level m=" << localiser.params().hierarchy.levels[l] << ": contains nearest "
              << s.level_contains_nearest[l] << "/" << s.queries << ", mean size "
              << s.level_mean_size[l] << " of " << memory.place_count() << "\n";
  }
  return s;
}

TEST(GridLocalisation, RandomPosesBetweenGridPointsLocaliseWithinOneSpacing) {
  const GridScores s = score(signature::ColourMode::kLuminance, 120);
  // At least 95% of queries at the finest level (docs/design.md, Evaluation: Localisation).
  EXPECT_GE(s.within_spacing, 0.95 * s.queries);
  // The best place of the pruned search is the exhaustive search's in ≥ 99% of queries.
  EXPECT_GE(s.pruned_equals_exhaustive, 0.99 * s.queries);
  // Coarse levels' candidate sets hold the true nearest place.
  for (std::size_t l = 0; l + 1 < s.level_contains_nearest.size(); ++l) {
    EXPECT_GE(s.level_contains_nearest[l], 0.95 * s.queries) << "level " << l;
  }
  // Coarse sets are wider than fine ones (Fig. 9).
  for (std::size_t l = 1; l < s.level_mean_size.size(); ++l) {
    EXPECT_LE(s.level_mean_size[l], s.level_mean_size[l - 1]);
  }
  // The query's heading, from the best place's (ground-truth) heading and the phases.
  EXPECT_LT(s.heading_errors_deg[s.queries / 2], 3.0);
  // Between places the position is nearer the truth than at the best place (queries lie
  // anywhere in the cells: the best place alone is off by up to half a diagonal).
  EXPECT_LT(median(s.between_errors_m), 0.8 * median(s.place_errors_m));
}

// A panorama straight from a camera or a renderer (cv::Mat) is localised as its signature is:
// the same best places; a panorama of other rows is refused naming it.
TEST(GridLocalisation, APanoramaIsLocalisedAsItsSignatureIs) {
  const VisualMemory memory = testing::grid_memory(signature::ColourMode::kLuminance);
  Localiser localiser(memory, {});
  signature::SignatureExtractor extractor(memory.parameters().signature);
  for (const testing::Query& q : testing::random_queries(5)) {
    const Localisation from_image = localiser.localise(q.frame.image, "q.png");
    const Localisation from_signature = localiser.localise(extractor.compute(q.frame.image));
    ASSERT_EQ(from_image.best.size(), from_signature.best.size());
    for (std::size_t i = 0; i < from_image.best.size(); ++i) {
      EXPECT_EQ(from_image.best[i].place, from_signature.best[i].place);
      EXPECT_EQ(from_image.best[i].dissimilarity, from_signature.best[i].dissimilarity);
    }
  }
  const cv::Mat taller(memory.parameters().panorama_rows + 4, 120, CV_8UC3, cv::Scalar(9, 80, 200));
  try {
    localiser.localise(taller, "tall.png");
    FAIL() << "a panorama of other rows was localised";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("tall.png: a panorama of"), std::string::npos)
        << error.what();
  }
}

TEST(GridLocalisation, ColourPerChannel) {
  const GridScores s = score(signature::ColourMode::kPerChannel, 60);
  EXPECT_GE(s.within_spacing, 0.95 * s.queries);
  EXPECT_GE(s.pruned_equals_exhaustive, 0.99 * s.queries);
}

// The fine level reorders the best places but reports Eq. 6's dissimilarity
// (navigation's match limit compares it with the map's links), and top_k places.
TEST(GridLocalisation, FineLevelKeepsEquationSixAndTopK) {
  const VisualMemory memory = testing::grid_memory();
  LocalisationParams params;
  params.top_k = 3;
  params.fine_candidates = 10;
  const Localiser localiser(memory, params);
  signature::SignatureExtractor extractor(memory.parameters().signature);
  const testing::Query q = testing::random_queries(1).front();
  const signature::Signature query = extractor.compute(q.frame.image);
  const Localisation result = localiser.localise(query);
  ASSERT_EQ(result.best.size(), 3u);
  for (const PlaceMatch& match : result.best) {
    const signature::Signature& place = memory.place(match.place).signature;
    EXPECT_NEAR(match.dissimilarity, signature::dissimilarity(place, query, 15), 1e-3);
    ASSERT_TRUE(match.rotational_dissimilarity.has_value());
    EXPECT_GE(*match.rotational_dissimilarity, 0.0);
  }
}

// A value set in code, as Python's writable fields set it, is refused by the localiser as the
// YAML loader refuses it in memory.yaml, naming the key (LocalisationParams::check, with the
// hierarchy's).
TEST(GridLocalisation, ParamsOutOfRangeAreRefusedByTheLocaliser) {
  const VisualMemory memory{MapParameters{}};
  const auto refusal = [&](const LocalisationParams& params) -> std::string {
    try {
      Localiser localiser(memory, params);
    } catch (const UsageError& error) {
      return error.what();
    }
    return "";
  };
  LocalisationParams top;
  top.top_k = 0;
  EXPECT_NE(refusal(top).find("localisation.top_k"), std::string::npos);
  LocalisationParams similarity;
  similarity.hierarchy.candidate_similarity = 2000.0;
  EXPECT_NE(refusal(similarity).find("localisation.candidate_similarity"), std::string::npos);
  LocalisationParams weight;
  weight.fine_rotational_weight = -1.0;
  EXPECT_NE(refusal(weight).find("localisation.fine_rotational_weight"), std::string::npos);
  EXPECT_EQ(refusal(LocalisationParams{}), "");
}

}  // namespace
}  // namespace omninav::memory
