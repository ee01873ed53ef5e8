// The belief over places (place_belief.hpp) on small graphs whose truth is known by construction.
#include "omninav/navigation/place_belief.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::navigation {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A corridor of `count` places 0.3 m apart along +x, every place facing +x: from each place the
// next lies ahead (0) and the previous behind (π).
std::vector<MeasuredLink> corridor(int count) {
  std::vector<MeasuredLink> links;
  for (int i = 0; i + 1 < count; ++i) {
    links.push_back({{i, i + 1}, 0.3, 0.0, kPi, LinkKind::kTravelled});
  }
  return links;
}

// The view at place `at` of a corridor whose places all look alike but for `distinct`: the
// dissimilarity to every place is `base`, to `at` itself 0 (when it is distinct).
std::vector<double> view_at(int count, int at, bool distinct) {
  std::vector<double> dissimilarity(count, 1.0);
  if (distinct) dissimilarity[at] = 0.0;
  return dissimilarity;
}

TEST(PlaceBelief, StartsUniformAndFollowsAView) {
  PlaceBelief belief(5, corridor(5), 1.0, BeliefParams{});
  for (int p = 0; p < 5; ++p) EXPECT_NEAR(belief.probability(p), 0.2, 1e-12);
  belief.update(view_at(5, 3, true));
  EXPECT_EQ(belief.most_likely(), 3);
  // exp(-1) to each of the four others.
  EXPECT_NEAR(belief.probability(3), 1.0 / (1.0 + 4.0 * std::exp(-1.0)), 1e-12);
}

TEST(PlaceBelief, MotionCarriesTheBeliefAlongTheLinkItAgreesWith) {
  BeliefParams params;
  params.uniform_share = 0.0;
  PlaceBelief belief(5, corridor(5), 1.0, params);
  belief.update(std::vector<double>{5.0, 5.0, 0.0, 5.0, 5.0});  // surely at 2
  ASSERT_EQ(belief.most_likely(), 2);
  // One link's length ahead: the belief moves to 3; 1 (behind) holds what came from 0 and, of
  // 2's, only the Gaussian's tail at 180° (exp(-8) for σ = 45°).
  const double at_zero = belief.probability(0);
  belief.predict(std::vector<double>(5, 0.0), 0.3);
  EXPECT_EQ(belief.most_likely(), 3);
  EXPECT_GT(belief.probability(3), 0.9);
  EXPECT_NEAR(belief.probability(1), at_zero, 1e-3);
  // Backwards: back to 2.
  belief.predict(std::vector<double>(5, kPi), 0.3);
  EXPECT_EQ(belief.most_likely(), 2);
  // Sideways (no link that way): most of the belief stays; what leaks (the direction's
  // uncertainty, exp(-2) a link at 90° for σ = 45°) leaks both ways alike.
  belief.predict(std::vector<double>(5, 0.5 * kPi), 0.3);
  EXPECT_EQ(belief.most_likely(), 2);
  EXPECT_GT(belief.probability(2), 0.5);
  EXPECT_NEAR(belief.probability(1) - belief.probability(3), 0.0, 0.02);
  // An unknown motion (NaN) keeps each place's probability.
  const std::vector<double> before = belief.probabilities();
  belief.predict(std::vector<double>(5, kNaN), 0.3);
  for (int p = 0; p < 5; ++p) EXPECT_NEAR(belief.probability(p), before[p], 1e-12);
}

// Two look-alike places of a corridor, 1 and 7: one view cannot tell them apart, the motion and
// the next view do. The robot stands at 1 and drives one link forwards, where the view is 2's.
TEST(PlaceBelief, MotionTellsLookAlikesApart) {
  BeliefParams params;
  params.uniform_share = 0.0;
  const int count = 9;
  PlaceBelief belief(count, corridor(count), 1.0, params);
  // At 1: looks exactly like 1 and like 7.
  std::vector<double> view(count, 3.0);
  view[1] = view[7] = 0.0;
  belief.update(view);
  EXPECT_NEAR(belief.probability(1), belief.probability(7), 1e-12);
  EXPECT_TRUE(belief.lost());
  // Forwards one link: the true view at 2 is distinct.
  belief.predict(std::vector<double>(count, 0.0), 0.3);
  std::vector<double> at_two(count, 3.0);
  at_two[2] = 0.0;
  belief.update(at_two);
  EXPECT_EQ(belief.most_likely(), 2);
  EXPECT_FALSE(belief.lost());
  EXPECT_GT(belief.probability(2), 0.9);
}

TEST(PlaceBelief, RepeatedLookAlikeViewsDoNotOutweighTheMotion) {
  // The belief is at 2 after moving; a view that matches a far place slightly better moves it
  // only gradually: exp(-Δ/τ) per view.
  BeliefParams params;
  params.uniform_share = 0.0;
  PlaceBelief belief(6, corridor(6), 1.0, params);
  belief.update(std::vector<double>{9.0, 9.0, 0.0, 9.0, 9.0, 9.0});
  std::vector<double> misleading(6, 9.0);
  misleading[2] = 0.6;
  misleading[5] = 0.5;  // the look-alike, a little better
  belief.update(misleading);
  EXPECT_EQ(belief.most_likely(), 2);
}

TEST(PlaceBelief, ABlockedLinkNoLongerCarriesTheBeliefUntilRestored) {
  BeliefParams params;
  params.uniform_share = 0.0;
  PlaceBelief belief(3, corridor(3), 1.0, params);
  belief.update(std::vector<double>{0.0, 9.0, 9.0});
  belief.remove_link(0, 1);
  belief.predict(std::vector<double>(3, 0.0), 0.3);
  EXPECT_EQ(belief.most_likely(), 0);
  EXPECT_NEAR(belief.neighbourhood_probability(0), belief.probability(0), 1e-12);
  // Restored, the link carries the belief again: a whole link's length moves it all.
  belief.restore_links();
  belief.predict(std::vector<double>(3, 0.0), 0.3);
  EXPECT_EQ(belief.most_likely(), 1);
  EXPECT_GT(belief.neighbourhood_probability(0), belief.probability(0));
}

TEST(PlaceBelief, RefusesWhatItCannotUse) {
  EXPECT_THROW(PlaceBelief(0, {}, 1.0, BeliefParams{}), UsageError);
  EXPECT_THROW(PlaceBelief(2, corridor(3), 1.0, BeliefParams{}), UsageError);
  EXPECT_THROW(PlaceBelief(3, corridor(3), 0.0, BeliefParams{}), UsageError);
  EXPECT_THROW(PlaceBelief(3, corridor(3), kNaN, BeliefParams{}), UsageError);
  PlaceBelief belief(3, corridor(3), 1.0, BeliefParams{});
  EXPECT_THROW(belief.update(std::vector<double>{1.0, 2.0}), UsageError);
  EXPECT_THROW(belief.predict(std::vector<double>(2, 0.0), 0.3), UsageError);
}

// A value set in code, as Python's writable fields set it, is refused by the belief as the YAML
// loader refuses it in navigation.yaml, naming the key (BeliefParams::check).
TEST(PlaceBelief, ParamsOutOfRangeAreRefusedNamingTheKey) {
  BeliefParams params;
  params.uniform_share = 0.75;
  try {
    PlaceBelief belief(5, corridor(5), 1.0, params);
    FAIL() << "a uniform share of 0.75 was accepted";
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find("belief.uniform_share"), std::string::npos);
  }
}

}  // namespace
}  // namespace omninav::navigation
