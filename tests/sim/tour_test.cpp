// The `tour` trajectory (a coverage planner's route) and wheel odometry beside the truth, judged
// against the worlds' own geometry: the free space, its regions, the exact poses.
#include "omninav/sim/tour.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/sim/trajectory.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::sim {
namespace {

std::vector<Eigen::Vector2d> positions(const Trajectory& trajectory) {
  std::vector<Eigen::Vector2d> route;
  for (const TimedPose& pose : trajectory.poses) route.push_back(pose.pose.floor_position());
  return route;
}

// A floor with no obstacles, as an OBJ world's bounding box is.
World bare_floor(double x_m, double y_m) {
  World world;
  world.floor = {0.0, 0.0, x_m, y_m};
  return world;
}

// Two halves of a floor that a wall from edge to edge keeps apart, each a named region.
World walled_in_halves() {
  World world = bare_floor(6.0, 4.0);
  world.obstacles.push_back({2.9, -1.0, 3.1, 5.0});
  world.regions = {{"west", {0.0, 0.0, 2.9, 4.0}}, {"east", {3.1, 0.0, 6.0, 4.0}}};
  return world;
}

TEST(Tour, CoversEveryRoomOfAHouseKeepingItsClearance) {
  // The full suite's house (three rooms either side of a corridor, furniture in each): every
  // room and the corridor are reached through their doorways, and nearly all of each one's
  // free floor lies within one lane of the tour (what stays out: corners and gaps behind
  // furniture narrower than the robot).
  for (const int seed : {1, 2}) {
    const World house = load_world(
        "house:rooms=3,room_min_m=2.5,room_max_m=3.5,seed=" + std::to_string(seed), WorldsConfig{});
    constexpr double kLane = 0.3, kClearance = 0.15;
    const Trajectory tour = make_trajectory("tour:lane_m=0.3,clearance_m=0.15,fps=5,seed=3", house);
    ASSERT_EQ(tour.kind, TrajectoryKind::kTour);
    for (std::size_t i = 0; i < tour.poses.size(); ++i) {
      const CameraPose& pose = tour.poses[i].pose;
      ASSERT_TRUE(house.is_free(pose.x_m, pose.y_m, kClearance - 1e-9)) << "pose " << i;
      if (i > 0) {
        const CameraPose& previous = tour.poses[i - 1].pose;
        ASSERT_TRUE(house.segment_is_free(previous.x_m, previous.y_m, pose.x_m, pose.y_m,
                                          kClearance - 1e-9))
            << "step to pose " << i;
        // Never faster than the default 0.2 m/s, corners included: 4 cm a frame at 5 fps.
        ASSERT_LE(std::hypot(pose.x_m - previous.x_m, pose.y_m - previous.y_m), 0.04 + 1e-9)
            << "step to pose " << i;
      }
    }
    const Coverage coverage = route_coverage(house, positions(tour), house.floor, kLane);
    EXPECT_GE(coverage.share, 0.95) << "seed " << seed;
    ASSERT_EQ(coverage.regions.size(), house.regions.size());
    for (const Coverage::RegionShare& region : coverage.regions) {
      EXPECT_GE(region.share, 0.9) << "seed " << seed << ", " << region.name;
    }
  }
}

TEST(Tour, IsSeededAndRestrictedToItsRectangle) {
  const World room = load_world("room", WorldsConfig{});
  const std::string spec = "tour:x0=1,y0=1,x1=4,y1=3,lane_m=0.4,clearance_m=0.2,fps=4";
  const Trajectory a = make_trajectory(spec + ",seed=5", room);
  const Trajectory b = make_trajectory(spec + ",seed=5", room);
  const Trajectory c = make_trajectory(spec + ",seed=6", room);
  ASSERT_EQ(a.poses.size(), b.poses.size());
  for (std::size_t i = 0; i < a.poses.size(); ++i) {
    EXPECT_EQ(a.poses[i].pose.x_m, b.poses[i].pose.x_m);
    EXPECT_EQ(a.poses[i].pose.y_m, b.poses[i].pose.y_m);
    EXPECT_EQ(a.poses[i].pose.heading_rad, b.poses[i].pose.heading_rad);
  }
  // Another seed starts elsewhere.
  EXPECT_GT(std::hypot(a.poses[0].pose.x_m - c.poses[0].pose.x_m,
                       a.poses[0].pose.y_m - c.poses[0].pose.y_m),
            0.05);
  for (const TimedPose& pose : a.poses) {
    EXPECT_GE(pose.pose.x_m, 1.0 - 1e-9);
    EXPECT_LE(pose.pose.x_m, 4.0 + 1e-9);
    EXPECT_GE(pose.pose.y_m, 1.0 - 1e-9);
    EXPECT_LE(pose.pose.y_m, 3.0 + 1e-9);
  }
}

TEST(Tour, CoversABareFloorInLanesAtTheGivenSpeed) {
  // An OBJ world has no obstacles: its floor's box is covered in lanes.
  const World floor = bare_floor(5.0, 3.0);
  const Trajectory tour = make_trajectory(
      "tour:lane_m=0.5,clearance_m=0.25,speed_m_s=0.25,fps=5,turn_rate_deg_s=0", floor);
  const Coverage coverage = route_coverage(floor, positions(tour), floor.floor, 0.5);
  EXPECT_GE(coverage.share, 0.99);
  EXPECT_NEAR(coverage.free_m2, 15.0, 0.1);
  // Lanes along the longer side, 2.5 m across at most 0.5 m apart: 6 lanes of 4.5 m, joined by
  // short steps, driven at 0.25 m/s (5 cm a frame; turns between two frames).
  EXPECT_GT(tour.length_m(), 6 * 4.5 - 0.1);
  EXPECT_LT(tour.length_m(), 6 * 4.5 + 5 * 0.5 + 4.0);  // and the way from a seeded start
  for (std::size_t i = 1; i < tour.poses.size(); ++i) {
    const CameraPose& a = tour.poses[i - 1].pose;
    const CameraPose& b = tour.poses[i].pose;
    EXPECT_LE(std::hypot(b.x_m - a.x_m, b.y_m - a.y_m), 0.05 + 1e-9);
  }
}

TEST(Tour, TurnsOnTheSpotAtTheGivenRate) {
  const World floor = bare_floor(4.0, 2.0);
  const Trajectory tour = make_trajectory(
      "tour:lane_m=0.5,clearance_m=0.25,fps=10,turn_rate_deg_s=30,x=0.25,y=0.25", floor);
  double largest_turn_deg = 0.0;
  for (std::size_t i = 1; i < tour.poses.size(); ++i) {
    largest_turn_deg =
        std::max(largest_turn_deg,
                 std::abs(rad_to_deg(signed_difference(tour.poses[i].pose.heading_rad,
                                                       tour.poses[i - 1].pose.heading_rad))));
  }
  EXPECT_LE(largest_turn_deg, 3.0 + 1e-9);  // 30°/s at 10 frames a second
}

TEST(Tour, PartsNoDoorwayJoinsAreAnErrorNamingThem) {
  const World halves = walled_in_halves();
  try {
    make_trajectory("tour:lane_m=0.3,clearance_m=0.2,x=1,y=1", halves);
    FAIL() << "a tour of two walled-off halves was accepted";
  } catch (const UsageError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("west"), std::string::npos) << message;
    EXPECT_NE(message.find("east"), std::string::npos) << message;
    EXPECT_NE(message.find("no free path"), std::string::npos) << message;
  }
  // Restricted to one half, the same world is toured.
  EXPECT_NO_THROW(make_trajectory("tour:x0=0,y0=0,x1=2.9,y1=4,lane_m=0.3,clearance_m=0.2", halves));
}

TEST(Tour, LaneAndClearanceThatLeaveNoPathAreRefusedWithTheKey) {
  const World floor = bare_floor(3.0, 3.0);
  const auto message = [&](const std::string& spec) {
    try {
      make_trajectory(spec, floor);
    } catch (const UsageError& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  EXPECT_NE(message("tour:clearance_m=1.6").find("clearance_m"), std::string::npos);
  EXPECT_NE(message("tour:clearance_m=1.6").find("no free floor"), std::string::npos);
  EXPECT_NE(message("tour:lane_m=0").find("lane_m"), std::string::npos);
  EXPECT_NE(message("tour:lane_m=-1").find("lane_m"), std::string::npos);
  EXPECT_NE(message("tour:clearance_m=-0.1").find("clearance_m"), std::string::npos);
  EXPECT_NE(message("tour:x0=2,x1=1").find("x1 > x0"), std::string::npos);
  EXPECT_NE(message("tour:x0=5,x1=6").find("no floor"), std::string::npos);
  EXPECT_NE(message("tour:speed_m_s=0").find("speed_m_s"), std::string::npos);
  EXPECT_NE(message("tour:lanes=3").find("unknown key 'lanes'"), std::string::npos);
}

TEST(Odometry, WithoutNoiseItIsTheTruth) {
  const World floor = bare_floor(5.0, 3.0);
  const Trajectory tour =
      make_trajectory("tour:lane_m=0.5,clearance_m=0.25,fps=5,odometry_noise=0", floor);
  for (const TimedPose& pose : tour.poses) {
    ASSERT_TRUE(pose.odometry.has_value());
    EXPECT_NEAR(pose.odometry->x_m, pose.pose.x_m, 1e-9);
    EXPECT_NEAR(pose.odometry->y_m, pose.pose.y_m, 1e-9);
    EXPECT_NEAR(signed_difference(pose.odometry->heading_rad, pose.pose.heading_rad), 0.0, 1e-9);
  }
  // Without the key, no odometry.
  EXPECT_FALSE(make_trajectory("tour:lane_m=0.5", floor).poses.back().odometry.has_value());
}

TEST(Odometry, DistanceAndTurnErrorsHaveTheGivenRelativeSpread) {
  // One metre straight ahead (one draw of the distance error), and a quarter turn on the spot
  // (one draw of the turn error), over many seeds: the measured length and turn are the true
  // ones times 1 + N(0, 0.1).
  const World floor = bare_floor(3.0, 3.0);
  std::vector<double> distance_errors, turn_errors;
  for (int seed = 1; seed <= 400; ++seed) {
    const std::string noise = ",odometry_noise=0.1,odometry_seed=" + std::to_string(seed);
    const Trajectory line =
        make_trajectory("line:x0=1,y0=1,x1=1.99,y1=1,speed_m_s=0.1,fps=10" + noise, floor);
    const CameraPose& first = *line.poses.front().odometry;
    const CameraPose& last = *line.poses.back().odometry;
    const double true_m = line.length_m();
    distance_errors.push_back(std::hypot(last.x_m - first.x_m, last.y_m - first.y_m) / true_m -
                              1.0);
    const Trajectory rotate =
        make_trajectory("rotate:x=1.5,y=1.5,turns=0.25,rate_deg_s=30,fps=10" + noise, floor);
    const double true_turn = signed_difference(rotate.poses.back().pose.heading_rad,
                                               rotate.poses.front().pose.heading_rad);
    const double measured = signed_difference(rotate.poses.back().odometry->heading_rad,
                                              rotate.poses.front().odometry->heading_rad);
    turn_errors.push_back(measured / true_turn - 1.0);
  }
  // 400 draws: the mean within 3 standard errors (0.015) of 0, the spread within 15 %.
  for (const std::vector<double>* errors : {&distance_errors, &turn_errors}) {
    double mean = 0.0, square = 0.0;
    for (const double e : *errors) mean += e / errors->size();
    for (const double e : *errors) square += (e - mean) * (e - mean) / (errors->size() - 1);
    EXPECT_NEAR(mean, 0.0, 0.015);
    EXPECT_NEAR(std::sqrt(square), 0.1, 0.015);
  }
}

}  // namespace
}  // namespace omninav::sim
