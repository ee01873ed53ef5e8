// The `wander` trajectory: an animal-like route with turns of varying sharpness and a wobbling
// heading, in the free space.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/sim/room.hpp"
#include "omninav/sim/trajectory.hpp"
#include "omninav/sim/world_loader.hpp"
#include "route_checks.hpp"

namespace omninav::sim {
namespace {

// Direction of travel between consecutive poses (of poses that moved).
std::vector<double> travel_directions(const Trajectory& trajectory) {
  std::vector<double> directions;
  for (std::size_t i = 1; i < trajectory.poses.size(); ++i) {
    const CameraPose& a = trajectory.poses[i - 1].pose;
    const CameraPose& b = trajectory.poses[i].pose;
    directions.push_back(std::atan2(b.y_m - a.y_m, b.x_m - a.x_m));
  }
  return directions;
}

TEST(Wander, StaysInTheFreeSpaceOfEveryFamily) {
  for (const std::string spec :
       {"room", "house:rooms=3,texture_px_per_m=20", "office:texture_px_per_m=20",
        "field:tussocks=100,texture_px_per_m=5"}) {
    const World world = load_world(spec, WorldsConfig{});
    const Trajectory route = make_trajectory("wander:length_m=40,fps=5,seed=3", world);
    ASSERT_FALSE(route.poses.empty());
    testing::expect_in_free_space(world, route, 0.24, spec);
    // It keeps moving: most of the asked length is travelled.
    EXPECT_GT(route.length_m(), 0.9 * 40.0) << spec;
  }
}

TEST(Wander, IsSeededAndTimedBySpeedAndFrameRate) {
  RoomParams params;
  params.texture_px_per_m = 10;
  const World room = make_room(params);
  const Trajectory a = make_trajectory("wander:length_m=6,speed_m_s=0.3,fps=10,seed=2", room);
  const Trajectory b = make_trajectory("wander:length_m=6,speed_m_s=0.3,fps=10,seed=2", room);
  const Trajectory c = make_trajectory("wander:length_m=6,speed_m_s=0.3,fps=10,seed=5", room);
  ASSERT_EQ(a.poses.size(), b.poses.size());
  EXPECT_EQ(a.poses.size(), 201u);  // 6 m at 0.3 m/s = 20 s at 10 frames/s, both ends
  EXPECT_NEAR(a.poses.back().time_s, 20.0, 1e-9);
  double differs = 0.0;
  for (std::size_t i = 0; i < a.poses.size(); ++i) {
    EXPECT_EQ(a.poses[i].pose.heading_rad, b.poses[i].pose.heading_rad);
    EXPECT_EQ(a.poses[i].pose.x_m, b.poses[i].pose.x_m);
    differs += std::abs(a.poses[i].pose.x_m - c.poses[i].pose.x_m);
  }
  EXPECT_GT(differs, 1.0);
  const Trajectory timed = make_trajectory("wander:duration_s=5,fps=4", room);
  EXPECT_EQ(timed.poses.size(), 21u);
  EXPECT_THROW(make_trajectory("wander:length_m=5,duration_s=5", room), UsageError);
  EXPECT_THROW(make_trajectory("wander:wobble_period_s=0", room), UsageError);
  EXPECT_THROW(make_trajectory("wander:wobble=3", room), UsageError);
  EXPECT_THROW(make_trajectory("wander:seed=-1", room), UsageError);
  EXPECT_THROW(make_trajectory("wander:seed=1.5", room), UsageError);
  EXPECT_THROW(make_trajectory("wander:length_m=1e12", room), UsageError);
}

TEST(Wander, HeadingWobblesAboutTheTravelAndTurnsVaryInSharpness) {
  World field;  // open ground: only the floor's edge, 50 m away, limits the route
  field.floor = {0.0, 0.0, 100.0, 100.0};
  const Trajectory route = make_trajectory(
      "wander:length_m=60,fps=10,speed_m_s=0.2,wobble_deg=20,wobble_period_s=2,seed=4", field);
  const std::vector<double> travel = travel_directions(route);
  // The heading minus the direction of travel swings by about ±20°, both ways.
  double largest = 0.0, smallest = 0.0;
  for (std::size_t i = 0; i < travel.size(); ++i) {
    const double offset = rad_to_deg(signed_difference(route.poses[i].pose.heading_rad, travel[i]));
    largest = std::max(largest, offset);
    smallest = std::min(smallest, offset);
  }
  EXPECT_GT(largest, 12.0);
  EXPECT_LT(largest, 30.0);
  EXPECT_LT(smallest, -12.0);
  EXPECT_GT(smallest, -30.0);
  // Turn rates of the travel (°/s): mostly gentle, some several times sharper.
  std::vector<double> rates;
  for (std::size_t i = 1; i < travel.size(); ++i) {
    rates.push_back(std::abs(rad_to_deg(signed_difference(travel[i], travel[i - 1]))) * 10.0);
  }
  std::sort(rates.begin(), rates.end());
  const double median = rates[rates.size() / 2], top = rates[rates.size() * 97 / 100];
  EXPECT_GT(median, 5.0);
  EXPECT_GT(top, 3.0 * median) << "median " << median << " °/s, 97th percentile " << top;
}

}  // namespace
}  // namespace omninav::sim
