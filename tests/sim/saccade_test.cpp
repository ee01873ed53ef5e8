// The `saccade` trajectory: straight stretches broken by sharp turns on the spot, stops and
// turns on the spot after them, measured on its poses (the ground truth).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/sim/room.hpp"
#include "omninav/sim/trajectory.hpp"
#include "omninav/sim/world_loader.hpp"
#include "route_checks.hpp"

namespace omninav::sim {
namespace {

// Open ground: only the floor's edge, 50 m from the start, limits the route.
World open_ground() {
  World field;
  field.floor = {0.0, 0.0, 100.0, 100.0};
  return field;
}

// One frame interval of a route: how far the camera moved and turned.
struct Interval {
  double moved_m = 0.0;
  double direction_rad = 0.0;  // of the move, when it moved
  double turned_rad = 0.0;     // heading change, signed
};

std::vector<Interval> intervals(const Trajectory& route) {
  std::vector<Interval> all;
  for (std::size_t i = 1; i < route.poses.size(); ++i) {
    const CameraPose& a = route.poses[i - 1].pose;
    const CameraPose& b = route.poses[i].pose;
    all.push_back({std::hypot(b.x_m - a.x_m, b.y_m - a.y_m),
                   std::atan2(b.y_m - a.y_m, b.x_m - a.x_m),
                   signed_difference(b.heading_rad, a.heading_rad)});
  }
  return all;
}

// The runs of consecutive intervals in which the camera stood (moved not at all): each a
// saccade, or a stop and the turn after it.
std::vector<std::vector<Interval>> still_runs(const std::vector<Interval>& all) {
  std::vector<std::vector<Interval>> runs;
  bool in_run = false;
  for (const Interval& interval : all) {
    if (interval.moved_m == 0.0) {
      if (!in_run) runs.emplace_back();
      runs.back().push_back(interval);
    }
    in_run = interval.moved_m == 0.0;
  }
  return runs;
}

TEST(Saccade, TurnsSharplyOnTheSpotByTheGivenAnglesAtTheGivenRate) {
  const Trajectory route = make_trajectory(
      "saccade:length_m=30,fps=10,stop_share=0,saccade_min_deg=40,saccade_max_deg=100,"
      "saccade_rate_deg_s=400,seed=2",
      open_ground());
  ASSERT_EQ(route.kind, TrajectoryKind::kSaccade);
  const std::vector<std::vector<Interval>> saccades = still_runs(intervals(route));
  // 30 m at 0.2 m/s in stretches of 2 s on average: some 75 stretches.
  ASSERT_GT(saccades.size(), 40u);
  int left = 0, right = 0;
  for (const std::vector<Interval>& saccade : saccades) {
    double total = 0.0;
    for (const Interval& frame : saccade) {
      // At most 400 °/s, 40° a frame; every frame of it turns (no stop: stop_share 0).
      EXPECT_LE(std::abs(frame.turned_rad), deg_to_rad(40.0) + 1e-9);
      EXPECT_GT(std::abs(frame.turned_rad), 0.0);
      total += frame.turned_rad;
    }
    EXPECT_GE(std::abs(total), deg_to_rad(40.0) - 1e-9);
    EXPECT_LE(std::abs(total), deg_to_rad(100.0) + 1e-9);
    // As few frames as the rate allows: a saccade spans 1-3 frames.
    EXPECT_EQ(saccade.size(),
              static_cast<std::size_t>(std::ceil(std::abs(total) / deg_to_rad(40.0) - 1e-9)));
    (total > 0 ? left : right) += 1;
  }
  EXPECT_GT(left, 10);
  EXPECT_GT(right, 10);
}

TEST(Saccade, StretchesAreStraightWithTheHeadingScanningAboutThem) {
  const Trajectory route = make_trajectory(
      "saccade:length_m=30,fps=10,speed_m_s=0.25,wobble_deg=12,wobble_period_s=1,seed=5",
      open_ground());
  const std::vector<Interval> all = intervals(route);
  double largest = 0.0, smallest = 0.0;
  int stretches = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (all[i].moved_m == 0.0) continue;
    EXPECT_NEAR(all[i].moved_m, 0.025, 1e-9);  // 0.25 m/s at 10 frames/s
    if (i > 0 && all[i - 1].moved_m > 0.0) {
      // Within a stretch the direction of travel does not change at all.
      EXPECT_NEAR(signed_difference(all[i].direction_rad, all[i - 1].direction_rad), 0.0, 1e-9);
    } else {
      ++stretches;
    }
    // The heading scans about the travel: ±12° give or take the jitter of 30 %.
    const double offset =
        rad_to_deg(signed_difference(route.poses[i + 1].pose.heading_rad, all[i].direction_rad));
    EXPECT_LE(std::abs(offset), 12.0 * 1.3 + 1e-9);
    largest = std::max(largest, offset);
    smallest = std::min(smallest, offset);
  }
  EXPECT_GT(stretches, 30);
  EXPECT_GT(largest, 8.0);
  EXPECT_LT(smallest, -8.0);
  // The route ends where its length is travelled.
  EXPECT_GE(route.length_m(), 30.0 - 1e-6);
  EXPECT_LT(route.length_m(), 30.0 + 0.025);
}

TEST(Saccade, StopsStandStillAndThenTurnOnTheSpot) {
  const Trajectory route = make_trajectory(
      "saccade:length_m=20,fps=10,stop_share=1,stop_s=2,spot_turn_rate_deg_s=45,seed=3",
      open_ground());
  const std::vector<std::vector<Interval>> stops = still_runs(intervals(route));
  ASSERT_GT(stops.size(), 20u);
  double longest_turn_deg = 0.0;
  for (const std::vector<Interval>& stop : stops) {
    // First it stands: no motion, no turn, for 0.5-1.5 times 2 s.
    std::size_t standing = 0;
    while (standing < stop.size() && stop[standing].turned_rad == 0.0) ++standing;
    EXPECT_GE(standing, 10u);
    EXPECT_LE(standing, 30u);
    // Then it turns on the spot at 45 °/s at most, by half a turn at most.
    double total = 0.0;
    for (std::size_t i = standing; i < stop.size(); ++i) {
      EXPECT_GT(std::abs(stop[i].turned_rad), 0.0);
      EXPECT_LE(std::abs(stop[i].turned_rad), deg_to_rad(4.5) + 1e-9);
      total += stop[i].turned_rad;
    }
    EXPECT_LE(std::abs(total), kPi + 1e-9);
    longest_turn_deg = std::max(longest_turn_deg, rad_to_deg(std::abs(total)));
  }
  EXPECT_GT(longest_turn_deg, 90.0);
}

TEST(Saccade, KeepsClearOfObstaclesInEveryFamily) {
  for (const std::string spec :
       {"room", "house:rooms=3,texture_px_per_m=20", "office:texture_px_per_m=20",
        "field:tussocks=100,texture_px_per_m=5"}) {
    const World world = load_world(spec, WorldsConfig{});
    const Trajectory route = make_trajectory("saccade:length_m=30,fps=5,seed=3", world);
    ASSERT_FALSE(route.poses.empty());
    testing::expect_in_free_space(world, route, 0.24, spec);
    EXPECT_GE(route.length_m(), 30.0 - 1e-6) << spec;
  }
}

TEST(Saccade, IsSeededAndTimedByTheFrameRate) {
  const World world = open_ground();
  const Trajectory a = make_trajectory("saccade:length_m=6,fps=10,seed=2", world);
  const Trajectory b = make_trajectory("saccade:length_m=6,fps=10,seed=2", world);
  const Trajectory c = make_trajectory("saccade:length_m=6,fps=10,seed=7", world);
  ASSERT_EQ(a.poses.size(), b.poses.size());
  double differs = 0.0;
  for (std::size_t i = 0; i < a.poses.size(); ++i) {
    EXPECT_EQ(a.poses[i].pose.heading_rad, b.poses[i].pose.heading_rad);
    EXPECT_EQ(a.poses[i].pose.x_m, b.poses[i].pose.x_m);
    EXPECT_NEAR(a.poses[i].time_s, i / 10.0, 1e-12);
    if (i < c.poses.size()) differs += std::abs(a.poses[i].pose.x_m - c.poses[i].pose.x_m);
  }
  EXPECT_GT(differs, 1.0);
  // Timed: 5 s at 4 frames/s, both ends.
  EXPECT_EQ(make_trajectory("saccade:duration_s=5,fps=4", world).poses.size(), 21u);
}

// The error `make_trajectory(spec)` throws holds every fragment, and is a bad spec's.
void expect_error(const std::string& spec, const World& world,
                  const std::vector<std::string>& fragments) {
  EXPECT_THROW(make_trajectory(spec, world), UsageError) << spec;
  testing::expect_trajectory_error(spec, world, fragments);
}

TEST(Saccade, BadParametersAreRefusedNamingTheKey) {
  const World world = open_ground();
  expect_error("saccade:stretch_s=0", world, {"saccade:stretch_s=0", "'stretch_s'"});
  expect_error("saccade:saccade_min_deg=-5", world, {"'saccade_min_deg'"});
  expect_error("saccade:saccade_max_deg=200", world, {"'saccade_max_deg'"});
  expect_error("saccade:saccade_min_deg=60,saccade_max_deg=50", world,
               {"'saccade_max_deg' = 50", "[60, 180]"});
  expect_error("saccade:saccade_rate_deg_s=0", world, {"'saccade_rate_deg_s'"});
  expect_error("saccade:stop_share=1.5", world, {"'stop_share'", "[0, 1]"});
  expect_error("saccade:stop_s=-1", world, {"'stop_s'"});
  expect_error("saccade:spot_turn_rate_deg_s=-30", world, {"'spot_turn_rate_deg_s'"});
  expect_error("saccade:wobble_period_s=0", world, {"wobble_period_s"});
  expect_error("saccade:clearance_m=-1", world, {"clearance_m"});
  expect_error("saccade:length_m=5,duration_s=5", world, {"length_m", "duration_s"});
  expect_error("saccade:speed_m_s=0", world, {"speed_m_s"});
  expect_error("saccade:saccade_deg=90", world, {"unknown key 'saccade_deg'", "saccade_max_deg"});
  expect_error("saccade:length_m=1e6,speed_m_s=0.001", world, {"more than 1000000 poses"});
  // A floor too small to take a step in any direction: boxed in, said so, not a hang.
  World tiny;
  tiny.floor = {0.0, 0.0, 0.1, 0.1};
  expect_error("saccade:clearance_m=0", tiny, {"boxed in"});
}

}  // namespace
}  // namespace omninav::sim
