#include "omninav/sim/virtual_robot.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/sim/room.hpp"

namespace omninav::sim {
namespace {

World bare_room() {
  RoomParams params;
  params.furniture_count = 0;
  params.texture_px_per_m = 10;
  return make_room(params);
}

TEST(VirtualRobot, NoiselessMovesAreExact) {
  const World world = bare_room();
  RobotParams params;
  params.turn_noise_deg = 0.0;
  params.distance_noise = 0.0;
  VirtualRobot robot(world, {1.0, 1.0, 1.0, 0.0, 0.0, 0.0}, params);
  EXPECT_NEAR(robot.move(deg_to_rad(90.0), 0.5), 0.5, 1e-9);
  EXPECT_NEAR(robot.pose().x_m, 1.0, 1e-9);
  EXPECT_NEAR(robot.pose().y_m, 1.5, 1e-9);
  EXPECT_NEAR(robot.pose().heading_rad, deg_to_rad(90.0), 1e-12);
  EXPECT_NEAR(robot.pose().z_m, 1.0, 0.0);
  // 90° at 90°/s, then 0.5 m at 0.2 m/s.
  EXPECT_NEAR(robot.elapsed_s(), 1.0 + 2.5, 1e-9);
}

TEST(VirtualRobot, StopsAtWallsKeepingItsClearance) {
  const World world = bare_room();  // 6 × 5 m
  RobotParams params;
  params.turn_noise_deg = 0.0;
  params.distance_noise = 0.0;
  params.radius_m = 0.2;
  VirtualRobot robot(world, {5.0, 2.0, 1.0, 0.0, 0.0, 0.0}, params);
  const double driven = robot.move(0.0, 3.0);
  EXPECT_NEAR(driven, 0.8, 0.011);  // up to x = 5.8, 0.2 m from the wall at x = 6
  EXPECT_TRUE(world.is_free(robot.pose().x_m, robot.pose().y_m, 0.2));
}

TEST(VirtualRobot, NoiseIsSeededAndHasTheRequestedSpread) {
  const World world = bare_room();
  RobotParams params;
  params.turn_noise_deg = 3.0;
  params.distance_noise = 0.0;
  double sum_sq = 0.0;
  const int moves = 400;
  VirtualRobot robot(world, {3.0, 2.5, 1.0, 0.0, 0.0, 0.0}, params);
  VirtualRobot twin(world, {3.0, 2.5, 1.0, 0.0, 0.0, 0.0}, params);
  double previous = 0.0;
  for (int i = 0; i < moves; ++i) {
    robot.move(0.0, 0.0);
    twin.move(0.0, 0.0);
    const double error = signed_difference(robot.pose().heading_rad, previous);
    previous = robot.pose().heading_rad;
    sum_sq += error * error;
  }
  EXPECT_EQ(robot.pose().heading_rad, twin.pose().heading_rad);
  EXPECT_NEAR(rad_to_deg(std::sqrt(sum_sq / moves)), 3.0, 0.4);
}

}  // namespace
}  // namespace omninav::sim
