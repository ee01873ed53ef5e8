// Plans over the motions measured from the phases (001_5bb151a4e28490b4.txt §3.4) instead of the
// lattice, with real recognition on a rendered grid of the built-in room
// (tests/support/room_navigation_map.hpp), judged against the renderer's poses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/evaluation/navigation_trials.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "support/room_navigation_map.hpp"

namespace omninav::navigation {
namespace {

using testing::kRoomGridSpacing_m;
using testing::RoomNavigation;

Eigen::Vector2d true_position(int place) {
  const CameraPose& pose = RoomNavigation::map().grid[place].pose;
  return {pose.x_m, pose.y_m};
}

// The places as the planner sees them, their lattice folded: every place right of the grid's
// middle mirrored onto the left half, so that places a metre apart lie on top of each other
// (what a spring lattice that folded does, measured without the truth by its motions).
std::vector<PlaceNode> folded_places() {
  std::vector<PlaceNode> places = RoomNavigation::map().places;
  double low = places.front().position_m.x(), high = low;
  for (const PlaceNode& place : places) {
    low = std::min(low, place.position_m.x());
    high = std::max(high, place.position_m.x());
  }
  const double middle = 0.5 * (low + high);
  for (PlaceNode& place : places) {
    if (place.position_m.x() > middle) place.position_m.x() = 2.0 * middle - place.position_m.x();
  }
  return places;
}

RouteParams motion_route() {
  RouteParams route;
  route.links = RouteParams::Links::kMotions;
  route.motion_neighbours = 4;
  return route;
}

TEST_F(RoomNavigation, MotionLinksPointWhereThePlacesTrulyLie) {
  const std::vector<MeasuredLink> links = motion_links(map().memory, map().places, motion_route());
  ASSERT_GT(links.size(), map().places.size());
  std::vector<double> errors_deg;
  int far = 0;
  for (const MeasuredLink& link : links) {
    const auto [a, b] = link.places;
    const Eigen::Vector2d ab = true_position(b) - true_position(a);
    if (ab.norm() > 2.0 * kRoomGridSpacing_m) {
      ++far;
      continue;
    }
    // Truly neighbours: the measured directions at both ends against the true bearings, each
    // relative to the place's true heading.
    const double at_a =
        signed_difference(std::atan2(ab.y(), ab.x()), map().grid[a].pose.heading_rad);
    const double at_b =
        signed_difference(std::atan2(-ab.y(), -ab.x()), map().grid[b].pose.heading_rad);
    errors_deg.push_back(
        rad_to_deg(std::abs(signed_difference(link.direction_at_first_rad, at_a))));
    errors_deg.push_back(
        rad_to_deg(std::abs(signed_difference(link.direction_at_second_rad, at_b))));
  }
  // Look-alikes (places more than two spacings apart) are few.
  EXPECT_LT(far, static_cast<int>(0.2 * links.size())) << far << " of " << links.size();
  EXPECT_LT(median(errors_deg), 10.0);
  EXPECT_LT(quantile(errors_deg, 0.9), 30.0);
}

TEST_F(RoomNavigation, MotionLinksDoNotReadTheLattice) {
  const std::vector<MeasuredLink> truth = motion_links(map().memory, map().places, motion_route());
  const std::vector<MeasuredLink> folded =
      motion_links(map().memory, folded_places(), motion_route());
  ASSERT_EQ(truth.size(), folded.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    EXPECT_EQ(truth[i].places, folded[i].places);
    EXPECT_EQ(truth[i].direction_at_first_rad, folded[i].direction_at_first_rad);
    EXPECT_EQ(truth[i].direction_at_second_rad, folded[i].direction_at_second_rad);
  }
}

// Seeded random trials in the room on the folded lattice: over the lattice's neighbours and its
// directions the robot is sent the wrong way, over the measured motions it reaches its goals.
TEST_F(RoomNavigation, OnAFoldedLatticeMotionLinksReachGoalsTheLatticeDoesNot) {
  std::vector<Eigen::Vector2d> mapped;
  for (const testing::StoredView& image : map().grid)
    mapped.emplace_back(image.pose.x_m, image.pose.y_m);
  evaluation::TrialParams params;
  params.count = 12;
  params.seed = 3;
  const std::vector<evaluation::Trial> trials =
      evaluation::random_trials(map().world, mapped, kRoomGridSpacing_m, 0.15, 1.0, params);
  const evaluation::TrialScene scene{map().world, *map().renderer, sim::RobotParams{}};

  GoalNavigationSetup setup = RoomNavigation::setup();
  setup.places = folded_places();
  setup.route.links = RouteParams::Links::kLattice;
  const evaluation::TrialSummary over_lattice =
      evaluation::summarise(evaluation::run_trials(trials, scene, setup, kRoomGridSpacing_m));
  setup.route = motion_route();
  setup.links = motion_links(map().memory, setup.places, setup.route);
  const evaluation::TrialSummary over_motions =
      evaluation::summarise(evaluation::run_trials(trials, scene, setup, kRoomGridSpacing_m));
  EXPECT_GE(over_motions.reached, 9) << over_motions.text();
  EXPECT_LE(over_lattice.reached, over_motions.reached - 4) << over_lattice.text();
}

}  // namespace
}  // namespace omninav::navigation
