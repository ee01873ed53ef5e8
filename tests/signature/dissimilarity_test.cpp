#include "omninav/signature/dissimilarity.hpp"

#include <gtest/gtest.h>

#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"
#include "rendered_room.hpp"

namespace omninav::signature {
namespace {

Signature tiny(std::vector<float> magnitude, int rows, int components) {
  Signature s;
  s.rows = rows;
  s.channels = 1;
  s.components = components;
  s.width_px = 64;
  s.magnitude = std::move(magnitude);
  s.phase_rad.assign(s.magnitude.size(), 0.f);
  return s;
}

TEST(Dissimilarity, EquationTwoByHand) {
  // Two rows, three components: Σ_y Σ_k |F_iy(k) − F_jy(k)|.
  const Signature a = tiny({10, 4, 1, 20, 2, 0}, 2, 3);
  const Signature b = tiny({12, 1, 1, 15, 2, 3}, 2, 3);
  EXPECT_DOUBLE_EQ(dissimilarity(a, b), 2 + 3 + 0 + 5 + 0 + 3);
  EXPECT_DOUBLE_EQ(dissimilarity(a, b, 1), 2 + 5);  // the first component only
  EXPECT_DOUBLE_EQ(dissimilarity(a, b, 2), 2 + 3 + 5 + 0);
  EXPECT_DOUBLE_EQ(dissimilarity(a, b), dissimilarity(b, a));
  EXPECT_DOUBLE_EQ(dissimilarity(a, a), 0.0);
  EXPECT_THROW(dissimilarity(a, b, 4), UsageError);
  EXPECT_THROW(dissimilarity(a, tiny({1, 2, 3}, 1, 3)), UsageError);
}

TEST(Dissimilarity, EquationSixWeightsEachComponent) {
  const Signature a = tiny({10, 4, 1, 20, 2, 0}, 2, 3);
  const Signature b = tiny({12, 1, 1, 15, 2, 3}, 2, 3);
  const ComponentWeights weights = parse_component_weights("0.5, 2", "test");  // α_2 = α_1 = 2
  EXPECT_DOUBLE_EQ(dissimilarity(a, b, -1, weights), 0.5 * (2 + 5) + 2 * (3 + 0) + 2 * (0 + 3));
  EXPECT_EQ(to_string(weights), "0.5,2");
  EXPECT_THROW(parse_component_weights("1, -1", "memory.yaml"), ConfigError);
  EXPECT_THROW(parse_component_weights("1, x", "memory.yaml"), ConfigError);
}

TEST(Similarity, EquationThreeRescalesToZeroToAThousand) {
  const std::vector<double> dis{10.0, 30.0, 20.0, 50.0};
  const std::vector<double> sim = rescale_similarities(dis);
  EXPECT_DOUBLE_EQ(sim[0], 1000.0);  // the least dissimilar
  EXPECT_DOUBLE_EQ(sim[3], 0.0);     // the most
  EXPECT_DOUBLE_EQ(sim[1], 500.0);
  EXPECT_DOUBLE_EQ(sim[2], 750.0);
  EXPECT_DOUBLE_EQ(similarity_0_1000(60.0, 10.0, 50.0), 0.0);  // clamped
  EXPECT_DOUBLE_EQ(similarity_0_1000(5.0, 5.0, 5.0), 1000.0);  // degenerate range
  EXPECT_TRUE(rescale_similarities({}).empty());
}

TEST(Dissimilarity, TurningOnTheSpotChangesAlmostNothingMovingChangesMuch) {
  SignatureExtractor extractor({15, ColourMode::kLuminance});
  const Signature here = extractor.compute(testing::render(2.5, 2.0, 0.0));
  const Signature turned = extractor.compute(testing::render(2.5, 2.0, 137.3));
  const Signature moved = extractor.compute(testing::render(2.8, 2.0, 0.0));
  // A sub-column turn resamples the image (anti-aliasing): a little change, far less than
  // 30 cm of travel.
  EXPECT_LT(dissimilarity(here, turned), 0.1 * dissimilarity(here, moved));
}

}  // namespace
}  // namespace omninav::signature
