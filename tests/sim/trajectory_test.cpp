#include "omninav/sim/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/sim/room.hpp"
#include "route_checks.hpp"

namespace omninav::sim {
namespace {

World empty_room() {
  RoomParams params;
  params.furniture_count = 0;
  params.texture_px_per_m = 10;
  return make_room(params);
}

TEST(Trajectory, RotateTurnsAtTheGivenRateOnTheSpot) {
  const World world = empty_room();
  const Trajectory rotate =
      make_trajectory("rotate:turns=3,rate_deg_s=-30,fps=10,x=2,y=1.5", world);
  ASSERT_EQ(rotate.poses.size(), 361u);  // 3 turns at 30°/s is 36 s, 10 frames a second, + start
  for (std::size_t i = 1; i < rotate.poses.size(); ++i) {
    EXPECT_NEAR(
        signed_difference(rotate.poses[i].pose.heading_rad, rotate.poses[i - 1].pose.heading_rad),
        deg_to_rad(-3.0), 1e-9);
    EXPECT_NEAR(rotate.poses[i].time_s - rotate.poses[i - 1].time_s, 0.1, 1e-12);
  }
  EXPECT_DOUBLE_EQ(rotate.poses.back().pose.x_m, 2.0);
  EXPECT_DOUBLE_EQ(rotate.poses.back().pose.z_m, 1.0);
  EXPECT_NEAR(rotate.length_m(), 0.0, 1e-12);
}

TEST(Trajectory, LineMovesAtTheGivenSpeedFacingForward) {
  const World world = empty_room();
  const Trajectory line = make_trajectory("line:x0=1,y0=1,x1=4,y1=3,speed_m_s=0.5,fps=5", world);
  const double heading = std::atan2(2.0, 3.0);
  for (std::size_t i = 1; i < line.poses.size(); ++i) {
    const auto& a = line.poses[i - 1].pose;
    const auto& b = line.poses[i].pose;
    EXPECT_NEAR(std::hypot(b.x_m - a.x_m, b.y_m - a.y_m) /
                    (line.poses[i].time_s - line.poses[i - 1].time_s),
                0.5, 1e-9);
    EXPECT_NEAR(b.heading_rad, heading, 1e-12);
  }
  // Frames come at fixed times, so the walk stops at the last frame before the far end.
  for (const TimedPose& pose : line.poses) {
    EXPECT_NEAR(pose.pose.x_m, 1.0 + 0.5 * pose.time_s * std::cos(heading), 1e-9);
    EXPECT_NEAR(pose.pose.y_m, 1.0 + 0.5 * pose.time_s * std::sin(heading), 1e-9);
  }
  EXPECT_NEAR(line.length_m(), std::hypot(3.0, 2.0), 0.5 / 5);
}

TEST(Trajectory, ZigZagTurnsOnTheSpotAtItsCorners) {
  const World world = empty_room();
  // Rows 1 m apart, 2 m long, at 0.5 m/s and 5 fps: 0.1 m a frame; 90°/s turns 18° a frame.
  const Trajectory zigzag = make_trajectory(
      "zigzag:x0=1,y0=1,x1=3,y1=3,rows=3,speed_m_s=0.5,fps=5,turn_rate_deg_s=90", world);
  int turning = 0;
  for (std::size_t i = 1; i < zigzag.poses.size(); ++i) {
    const auto& a = zigzag.poses[i - 1].pose;
    const auto& b = zigzag.poses[i].pose;
    const double moved = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
    const double turned = std::fabs(signed_difference(b.heading_rad, a.heading_rad));
    // A frame either moves along the heading or turns on the spot, never both, and never faster.
    EXPECT_LE(moved, 0.1 + 1e-9) << i;
    EXPECT_LE(turned, deg_to_rad(18.0) + 1e-9) << i;
    if (turned > 1e-12) {
      ++turning;
      EXPECT_NEAR(moved, 0.0, 1e-12) << i;
    } else if (moved > 1e-12) {
      EXPECT_NEAR(std::atan2(b.y_m - a.y_m, b.x_m - a.x_m), b.heading_rad, 1e-9) << i;
    }
  }
  // Four corners of 90° at 18° a frame.
  EXPECT_EQ(turning, 4 * 5);
  EXPECT_NEAR(zigzag.length_m(), 3 * 2.0 + 2 * 1.0, 0.1);
  // turn_rate_deg_s = 0: the heading jumps at the corners, between two frames.
  const Trajectory sudden = make_trajectory(
      "zigzag:x0=1,y0=1,x1=3,y1=3,rows=3,speed_m_s=0.5,fps=5,turn_rate_deg_s=0", world);
  EXPECT_EQ(zigzag.poses.size() - sudden.poses.size(), 4u * 5u);
  EXPECT_THROW(make_trajectory("zigzag:turn_rate_deg_s=-1", world), UsageError);
}

TEST(Trajectory, CircleStaysOnItsRadiusWithTangentHeading) {
  const World world = empty_room();
  const Trajectory circle = make_trajectory("circle:cx=3,cy=2.5,radius_m=1.5,speed_m_s=0.3", world);
  for (const TimedPose& pose : circle.poses) {
    const double dx = pose.pose.x_m - 3.0, dy = pose.pose.y_m - 2.5;
    EXPECT_NEAR(std::hypot(dx, dy), 1.5, 1e-9);
    // Counter-clockwise: heading is the radius direction plus 90°.
    EXPECT_NEAR(signed_difference(pose.pose.heading_rad, std::atan2(dy, dx) + kPi / 2), 0.0, 1e-9);
  }
  EXPECT_NEAR(circle.length_m(), kTwoPi * 1.5, 0.05);
}

TEST(Trajectory, GridCarriesIndicesAndSkipsFurniture) {
  const World empty = empty_room();
  const Trajectory grid = make_trajectory("grid:x0=0.5,y0=0.5,nx=10,ny=8,spacing_m=0.3", empty);
  ASSERT_EQ(grid.poses.size(), 80u);
  EXPECT_EQ(grid.poses[13].grid.value()[0], 3);
  EXPECT_EQ(grid.poses[13].grid.value()[1], 1);
  EXPECT_NEAR(grid.poses[13].pose.x_m, 0.5 + 3 * 0.3, 1e-12);
  EXPECT_NEAR(grid.poses[13].pose.y_m, 0.5 + 1 * 0.3, 1e-12);

  const World furnished = make_room({});
  const Trajectory sparse =
      make_trajectory("grid:x0=0.3,y0=0.3,nx=18,ny=15,spacing_m=0.3", furnished);
  EXPECT_LT(sparse.poses.size(), 18u * 15u);
  for (const TimedPose& pose : sparse.poses)
    EXPECT_TRUE(furnished.is_free(pose.pose.x_m, pose.pose.y_m));
}

TEST(Trajectory, WalkAvoidsFurnitureAndIsSeeded) {
  const World world = make_room({});
  const Trajectory a = make_trajectory("walk:x=0.4,y=0.4,steps=300,seed=3", world);
  const Trajectory b = make_trajectory("walk:x=0.4,y=0.4,steps=300,seed=3", world);
  ASSERT_EQ(a.poses.size(), 300u);
  for (std::size_t i = 0; i < a.poses.size(); ++i) {
    EXPECT_EQ(a.poses[i].pose.x_m, b.poses[i].pose.x_m);
    EXPECT_TRUE(world.is_free(a.poses[i].pose.x_m, a.poses[i].pose.y_m)) << i;
  }
}

TEST(Trajectory, BumpyRunsTiltWithTheRequestedSpread) {
  const World world = empty_room();
  const Trajectory bumpy =
      make_trajectory("line:speed_m_s=0.05,fps=20,pitch_noise_deg=3,roll_noise_deg=2", world);
  double pitch_sq = 0.0, roll_sq = 0.0;
  for (const TimedPose& pose : bumpy.poses) {
    pitch_sq += pose.pose.pitch_rad * pose.pose.pitch_rad;
    roll_sq += pose.pose.roll_rad * pose.pose.roll_rad;
  }
  EXPECT_NEAR(rad_to_deg(std::sqrt(pitch_sq / bumpy.poses.size())), 3.0, 0.6);
  EXPECT_NEAR(rad_to_deg(std::sqrt(roll_sq / bumpy.poses.size())), 2.0, 0.4);
}

TEST(Trajectory, ReadsPosesFromCsv) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "omninav_trajectory.csv";
  std::ofstream(file) << "heading_deg,x_m,y_m,z_m\n90,1,2,0.5\n-90,1.5,2,0.5\n";
  const Trajectory csv = make_trajectory("csv:path=" + file.string() + ",fps=4", empty_room());
  ASSERT_EQ(csv.poses.size(), 2u);
  EXPECT_NEAR(csv.poses[0].pose.heading_rad, kPi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(csv.poses[1].pose.x_m, 1.5);
  EXPECT_DOUBLE_EQ(csv.poses[1].pose.z_m, 0.5);
  EXPECT_DOUBLE_EQ(csv.poses[1].time_s, 0.25);
  std::ofstream(file) << "x_m,y_m\n1,2\n";
  EXPECT_THROW(make_trajectory("csv:path=" + file.string(), empty_room()), InputError);
  std::ofstream(file) << "x_m,y_m,heading_deg\n1,two,3\n";
  try {
    make_trajectory("csv:path=" + file.string(), empty_room());
    FAIL();
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(file.string() + ":2"), std::string::npos)
        << error.what();
  }
  std::ofstream(file) << "x_m,y_m,heading_deg\n1,2,3\n1e157,2,3\n";  // 1e160 mm
  try {
    make_trajectory("csv:path=" + file.string(), empty_room());
    FAIL();
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(file.string() + ":3: 1e+157 m is not a position"),
              std::string::npos)
        << error.what();
  }
  std::filesystem::remove(file);
}

TEST(Trajectory, BadSpecsNameTheProblem) {
  const World world = empty_room();
  EXPECT_THROW(make_trajectory("spiral", world), UsageError);
  EXPECT_THROW(make_trajectory("rotate:rate_deg_s=0", world), UsageError);
  EXPECT_THROW(make_trajectory("line:speed=0.2", world), UsageError);  // speed_m_s, not speed
  // A value that is not a number is a bad spec like the others, whichever key.
  EXPECT_THROW(make_trajectory("line:speed_m_s=fast", world), UsageError);
  EXPECT_THROW(make_trajectory("circle:radius_m", world), UsageError);
  try {
    make_trajectory("line:sped_m_s=0.2", world);
    FAIL();
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find("sped_m_s"), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("speed_m_s"), std::string::npos);
  }
}

// Every substring of the error `make_trajectory(spec)` throws in the empty room.
void expect_error(const std::string& spec, const std::vector<std::string>& fragments) {
  testing::expect_trajectory_error(spec, empty_room(), fragments);
}

TEST(Trajectory, AKeyGivenTwiceIsAnError) {
  expect_error("grid:nx=2,nx=3", {"grid:nx=2,nx=3", "'nx' is given twice"});
  expect_error("line: speed_m_s=0.2 , speed_m_s = 0.3", {"'speed_m_s' is given twice"});
}

TEST(Trajectory, NonFiniteAbsurdAndFractionalCountsAreErrors) {
  expect_error("line:x0=nan", {"x0", "'nan' is not a number"});
  expect_error("line:x1=inf", {"x1"});
  expect_error("circle:cx=1e160", {"cx", "beyond"});
  expect_error("grid:nx=2.5", {"nx", "whole number"});
  // Counts that would overflow an int, or fill memory with poses.
  expect_error("rotate:turns=1e6,rate_deg_s=1e-6", {"more than 1000000 poses"});
  expect_error("grid:nx=100000,ny=100000", {"more than 1000000 poses"});
  expect_error("walk:steps=2000000", {"more than 1000000 poses"});
  expect_error("line:x0=0,x1=1e6,speed_m_s=1e-6", {"more than 1000000 poses"});
  // A negative seed is still a seed.
  EXPECT_EQ(make_trajectory("walk:steps=5,seed=-3", empty_room()).poses.size(), 5u);
}

}  // namespace
}  // namespace omninav::sim
