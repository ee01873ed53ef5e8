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

// `count` seeded random trials among the grid's places (navigate --trials).
std::vector<evaluation::Trial> room_trials(int count, unsigned seed) {
  std::vector<Eigen::Vector2d> mapped;
  for (const testing::StoredView& image : RoomNavigation::map().grid)
    mapped.emplace_back(image.pose.x_m, image.pose.y_m);
  evaluation::TrialParams params;
  params.count = count;
  params.seed = seed;
  return evaluation::random_trials(RoomNavigation::map().world, mapped, kRoomGridSpacing_m, 0.15,
                                   1.0, params);
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
  const std::vector<evaluation::Trial> trials = room_trials(12, 3);
  const evaluation::TrialScene scene{map().world, *map().renderer, sim::RobotParams{}};

  GoalNavigationSetup setup = RoomNavigation::setup();
  setup.places = folded_places();
  // The stall's metres as goal_navigation_setup sets them on a map that states its spacing (a
  // grid database's): this map does not, and the folded lattice's spacing is not the map's.
  setup.navigator.stall_m = setup.navigator.stall_spacings * kRoomGridSpacing_m;
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

// The measured motions with every link that truly crosses the line x = `cut_m` pointing back at
// both ends (its directions turned by 180°): a robot sent across by one is sent back by the
// place it reaches, as by a look-alike's fit, and swings there.
std::vector<MeasuredLink> links_pointing_back_across(double cut_m) {
  std::vector<MeasuredLink> links =
      motion_links(RoomNavigation::map().memory, RoomNavigation::map().places, motion_route());
  int crossing = 0;
  for (MeasuredLink& link : links) {
    const double xa = true_position(link.places.first).x();
    const double xb = true_position(link.places.second).x();
    if ((xa < cut_m) == (xb < cut_m)) continue;
    link.direction_at_first_rad = wrap_angle(link.direction_at_first_rad + M_PI);
    link.direction_at_second_rad = wrap_angle(link.direction_at_second_rad + M_PI);
    ++crossing;
  }
  EXPECT_GE(crossing, 4);
  return links;
}

// Seeded random trials whose start and goal truly lie either side of the middle of the grid,
// over the motions with the links across pointing back: the robot stalls on them, drops them
// and switches to the lattice's plan (here the truth), and reaches its goal; without the stall
// it swings until its budget is spent or gives up.
TEST_F(RoomNavigation, AStalledRobotSwitchesFromBackPointingMotionsToTheLattice) {
  const double cut_m = 1.2 + 4.5 * kRoomGridSpacing_m;  // between the grid's 5th and 6th columns
  std::vector<evaluation::Trial> trials;
  for (const evaluation::Trial& trial : room_trials(24, 5)) {
    if ((trial.start.x_m < cut_m) != (trial.goal.x_m < cut_m)) trials.push_back(trial);
  }
  ASSERT_GE(trials.size(), 8u);
  trials.resize(8);
  const evaluation::TrialScene scene{map().world, *map().renderer, sim::RobotParams{}};

  GoalNavigationSetup setup = RoomNavigation::setup();
  setup.route = motion_route();
  setup.links = links_pointing_back_across(cut_m);
  setup.navigator.stall_spacings = 0.0;
  const evaluation::TrialSummary swinging =
      evaluation::summarise(evaluation::run_trials(trials, scene, setup, kRoomGridSpacing_m));
  setup.navigator.stall_spacings = NavigatorParams{}.stall_spacings;  // as shipped
  const std::vector<evaluation::TrialOutcome> outcomes =
      evaluation::run_trials(trials, scene, setup, kRoomGridSpacing_m);
  const evaluation::TrialSummary stalling = evaluation::summarise(outcomes);
  // Measured with the shipped stall (8 spacings): 7 of 8 reached (7 switched), 0 of 8 without
  // (6 gave up); with 4 spacings 8 of 8.
  EXPECT_GE(stalling.reached, 6) << stalling.text();
  EXPECT_LE(swinging.reached, stalling.reached - 4) << swinging.text();
  int switched = 0;
  for (const evaluation::TrialOutcome& outcome : outcomes)
    switched += outcome.result.link_switches > 0 ? 1 : 0;
  EXPECT_GE(switched, 6);
}

}  // namespace
}  // namespace omninav::navigation
