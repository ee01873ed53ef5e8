#include "omninav/signature/dissimilarity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <opencv2/core.hpp>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/signature/phase_heading.hpp"
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

// The rotational dissimilarity by hand: one line, two components, F_from = (3, 2·e^{i·0.5}),
// F_to = (4, 1·e^{i·0.2}). At a turn δ, |F_to(k) − e^{−ikδ}F_from(k)| per component.
TEST(RotationalDissimilarity, CoefficientsAlignedByTheTurnByHand) {
  Signature from = tiny({3, 2}, 1, 2);
  from.phase_rad = {0.f, 0.5f};
  Signature to = tiny({4, 1}, 1, 2);
  to.phase_rad = {0.f, 0.2f};
  const double turn = 0.3;  // e^{−iδ}·2e^{i0.5} = 2e^{i0.2}: aligned with to's phase
  EXPECT_NEAR(rotational_dissimilarity(from, to, turn), 1.0 + 1.0, 1e-6);
  const double other = -0.4;  // misaligned by 0.7 rad: |e^{i0.2} − 2e^{i0.9}|
  EXPECT_NEAR(rotational_dissimilarity(from, to, other),
              1.0 + std::abs(std::polar(1.0, 0.2) - std::polar(2.0, 0.9)), 1e-6);
  // Weights: α_k per component.
  const ComponentWeights weights = parse_component_weights("2, 3", "test");
  EXPECT_NEAR(rotational_dissimilarity(from, to, turn, -1, weights), 2.0 * 1.0 + 3.0 * 1.0, 1e-6);
  EXPECT_THROW(rotational_dissimilarity(from, tiny({1, 2, 3}, 1, 3), turn, 3), UsageError);
}

// A panorama and its mirror image hold the same magnitudes (Eq. 2 sees no difference) but not
// the same arrangement along the horizon: the rotational dissimilarity sees it, at any turn,
// and is ~0 for the same view turned on the spot, at the turn the phases give.
TEST(RotationalDissimilarity, TellsAMirrorFromATurnWhereMagnitudesCannot) {
  SignatureExtractor extractor({15, ColourMode::kLuminance});
  const cv::Mat view = testing::render(2.5, 2.0, 0.0);
  cv::Mat mirrored;
  cv::flip(view, mirrored, 1);
  const Signature here = extractor.compute(view);
  const Signature mirror = extractor.compute(mirrored);
  const Signature turned = extractor.compute(roll_columns(view, 40));
  const double turn_rad = relative_heading(here, turned).turn_rad;
  EXPECT_NEAR(turn_rad, rotation_of_shift_px(40, view.cols), 1e-3);
  EXPECT_LT(dissimilarity(here, mirror), 0.05);  // float rounding over 675 values
  double least_mirror = std::numeric_limits<double>::infinity();
  for (int step = 0; step < 360; ++step) {
    least_mirror = std::min(least_mirror, rotational_dissimilarity(here, mirror, kPi * step / 180));
  }
  const double aligned = rotational_dissimilarity(here, turned, turn_rad);
  EXPECT_LT(aligned, 0.01 * least_mirror);
  // Never below Eq. 2: |a − b| ≥ ||a| − |b||.
  for (double turn : {0.0, 0.7, turn_rad}) {
    EXPECT_GE(rotational_dissimilarity(here, mirror, turn), dissimilarity(here, mirror) - 1e-6);
  }
}

}  // namespace
}  // namespace omninav::signature
