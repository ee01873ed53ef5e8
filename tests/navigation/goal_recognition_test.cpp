// The goal image's place (recognise_goal, goal_navigation.hpp) against the renderer's poses. A
// look-alike is made by giving a place far from the goal the goal image's own signature (and
// having the localiser name it): by the signature alone it is the goal's place. Min-warping, which
// compares the whole images, must find the place the goal image was truly taken beside, when
// the signature puts that place on the shortlist.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "omninav/core/errors.hpp"
#include "omninav/navigation/goal_navigation.hpp"
#include "support/room_navigation_map.hpp"

namespace omninav::navigation {
namespace {

using testing::RoomNavigation;

class GoalRecognitionTest : public RoomNavigation {
 protected:
  void SetUp() override {
    setup_ = setup();
    // The goal 8 cm from place `near_` (by truth); `far_` is the place farthest from it.
    const CameraPose& at = map().grid[near_].pose;
    CameraPose goal = at;
    goal.x_m += 0.08;
    goal.heading_rad += 1.0;
    goal_image_ = map().renderer->render(goal);
    double farthest = 0.0;
    for (std::size_t p = 0; p < map().grid.size(); ++p) {
      const double distance = place_distance_m(p, goal.x_m, goal.y_m);
      if (distance > farthest) {
        farthest = distance;
        far_ = static_cast<int>(p);
      }
    }
    ASSERT_GT(farthest, 2.0);
    ASSERT_EQ(nearest_place(goal.x_m, goal.y_m), near_);
    // The look-alike: the far place's signature is the goal image's, and the localiser names it.
    setup_.signatures[far_] = setup_.signature_of(goal_image_);
    setup_.localise = [this](const cv::Mat&) {
      memory::Localisation localisation;
      memory::PlaceMatch match;
      match.place = static_cast<memory::PlaceIndex>(far_);
      localisation.best.push_back(match);
      return localisation;
    };
    std::vector<double> dissimilarity(setup_.places.size());
    place_dissimilarities(setup_, setup_.signature_of(goal_image_), dissimilarity);
    ASSERT_EQ(dissimilarity[far_], 0.0);
    // How far down the signature's ranking the goal's own place is, in the shortlist's unit.
    near_ratio_ = dissimilarity[near_] / setup_.link_dissimilarity;
    ASSERT_GT(near_ratio_, 0.0);
  }

  GoalNavigationSetup setup_;
  cv::Mat goal_image_;
  int near_ = 20;
  int far_ = -1;
  double near_ratio_ = 0.0;
};

TEST_F(GoalRecognitionTest, MinWarpingFindsTheGoalsPlaceAmongItsLookAlikes) {
  setup_.goal_shortlist_ratio = 2.0 * near_ratio_;  // the goal's own place on the shortlist
  const memory::PlaceMatch goal = recognise_goal(setup_, goal_image_, "goal.png");
  EXPECT_EQ(static_cast<int>(goal.place), near_);
  EXPECT_GT(goal.dissimilarity_per_value, 0.0);
}

TEST_F(GoalRecognitionTest, APlaceTheSignatureSetsApartIsNotOnTheShortlist) {
  setup_.goal_shortlist_ratio = 0.5 * near_ratio_;
  EXPECT_EQ(static_cast<int>(recognise_goal(setup_, goal_image_, "goal.png").place), far_);
}

TEST_F(GoalRecognitionTest, WithoutThumbnailsTheSignatureDecides) {
  setup_.goal_shortlist_ratio = 2.0 * near_ratio_;
  setup_.snapshots.reset();
  EXPECT_EQ(static_cast<int>(recognise_goal(setup_, goal_image_, "goal.png").place), far_);
}

TEST_F(GoalRecognitionTest, AGoalImageThatMatchesNoPlaceIsRefusedByName) {
  setup_.localise = map().localise;
  setup_.match_limit = 0.0;
  try {
    recognise_goal(setup_, goal_image_, "goal.png");
    FAIL() << "a goal image beyond the match limit was recognised";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("goal.png"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace omninav::navigation
