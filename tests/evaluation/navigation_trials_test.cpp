// Navigation trials and the robot worlds, with real recognition on a map of the built-in room
// (tests/support/room_navigation_map.hpp), judged against the renderer's poses.
#include "omninav/evaluation/navigation_trials.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/evaluation/robot_worlds.hpp"
#include "support/room_navigation_map.hpp"

namespace omninav::evaluation {
namespace {

using navigation::GoalRun;
using navigation::NavigationStep;
using testing::kRoomGridSpacing_m;
using testing::RoomNavigation;

// The grid's panoramas as a grid world's images.
std::vector<GridImage> grid_images() {
  std::vector<GridImage> images;
  for (const testing::StoredView& view : RoomNavigation::map().grid)
    images.push_back({view.panorama, view.pose});
  return images;
}

TEST_F(RoomNavigation, AShortNavigationInTheRoomReachesItsGoal) {
  // Between places, 1.8 m apart past the end of a table (the box at x 2.57..3.54 m,
  // y 1.85..2.16 m of this room), the goal seen facing elsewhere than the robot will arrive.
  const CameraPose start{2.55, 1.15, 1.0, deg_to_rad(150.0), 0.0, 0.0};
  const CameraPose goal{2.3, 2.9, 1.0, deg_to_rad(-60.0), 0.0, 0.0};
  ASSERT_TRUE(map().world.is_free(start.x_m, start.y_m, 0.15));
  ASSERT_TRUE(map().world.is_free(goal.x_m, goal.y_m, 0.15));
  sim::VirtualRobot robot(map().world, start, sim::RobotParams{});
  RenderedWorld world(robot, *map().renderer);
  const GoalRun run =
      navigation::navigate_to_image(world, map().renderer->render(goal), "goal", setup());
  // The goal image is recognised as a place it was taken beside (recognise_goal): not the
  // nearest here (0.14 m), the one min-warping matches best (0.22 m); homing covers the rest.
  EXPECT_LT(place_distance_m(run.goal.place, goal.x_m, goal.y_m), kRoomGridSpacing_m);
  ASSERT_TRUE(run.result.reached) << run.result.steps.size() << " steps";
  // Stopped within one grid spacing of the goal pose (the robot stops once it recognises the
  // goal's place, which lies within half a cell's diagonal of the goal).
  EXPECT_LT(std::hypot(robot.pose().x_m - goal.x_m, robot.pose().y_m - goal.y_m),
            kRoomGridSpacing_m);
  const double straight_m = std::hypot(goal.x_m - start.x_m, goal.y_m - start.y_m);
  EXPECT_LT(run.result.path_length_m, 1.5 * straight_m);
}

TEST_F(RoomNavigation, HeadingsReadFromThePlacesMatchTheTruth) {
  // Each step's heading estimate (lattice frame) plus the first place's heading is the robot's
  // true heading, within the phase estimate's error (a few degrees on a 180-column panorama).
  const CameraPose start{2.4, 1.3, 1.0, deg_to_rad(100.0), 0.0, 0.0};
  const CameraPose goal{1.5, 2.5, 1.0, 0.0, 0.0, 0.0};
  sim::VirtualRobot robot(map().world, start, sim::RobotParams{});
  RenderedWorld world(robot, *map().renderer);
  const GoalRun run =
      navigation::navigate_to_image(world, map().renderer->render(goal), "goal", setup());
  ASSERT_FALSE(run.result.steps.empty());
  const double first_heading = *map().memory.place(0).heading_rad;
  for (const NavigationStep& step : run.result.steps) {
    EXPECT_LT(std::abs(rad_to_deg(signed_difference(step.heading_estimate_rad + first_heading,
                                                    step.truth.heading_rad))),
              10.0)
        << "step " << step.index;
  }
}

TEST_F(RoomNavigation, SeededTrialsReachTheirGoals) {
  // The machinery of the navigation target (100 random pairs; omninav navigate --trials), on a
  // few pairs in the mapped area.
  std::vector<Eigen::Vector2d> mapped;
  for (const testing::StoredView& image : map().grid)
    mapped.emplace_back(image.pose.x_m, image.pose.y_m);
  TrialParams params;
  params.count = 4;
  params.seed = 5;
  const std::vector<Trial> trials =
      random_trials(map().world, mapped, kRoomGridSpacing_m, 0.15, 1.0, params);
  ASSERT_EQ(trials.size(), 4u);
  for (const Trial& trial : trials) {
    for (const CameraPose& pose : {trial.start, trial.goal}) {
      EXPECT_TRUE(map().world.is_free(pose.x_m, pose.y_m, 0.15));
      double nearest = 1e9;
      for (const Eigen::Vector2d& point : mapped)
        nearest = std::min(nearest, std::hypot(point.x() - pose.x_m, point.y() - pose.y_m));
      EXPECT_LE(nearest, kRoomGridSpacing_m);
    }
    EXPECT_GE(std::hypot(trial.goal.x_m - trial.start.x_m, trial.goal.y_m - trial.start.y_m),
              3 * kRoomGridSpacing_m);
  }
  // Same seed, same trials.
  const std::vector<Trial> again =
      random_trials(map().world, mapped, kRoomGridSpacing_m, 0.15, 1.0, params);
  EXPECT_EQ(again.front().goal.x_m, trials.front().goal.x_m);

  const std::vector<TrialOutcome> outcomes = run_trials(
      trials, {map().world, *map().renderer, sim::RobotParams{}}, setup(), kRoomGridSpacing_m);
  for (const TrialOutcome& outcome : outcomes) {
    EXPECT_TRUE(outcome.reached) << "goal " << outcome.trial.goal.x_m << ","
                                 << outcome.trial.goal.y_m << " missed by " << outcome.final_error_m
                                 << " m";
  }
  const TrialSummary summary = summarise(outcomes);
  EXPECT_EQ(summary.reached, 4);
  // The path target (≤ 1.5 × the straight line) is not quite met round this room's table: the
  // robot drives place to place and learns the blocked links by meeting them (1.64 measured
  // steering by the next place's image, 2.5 by the plan's directions and with sidesteps of at
  // most 60°; the full suite's figures are in docs/evaluation.md). Bounded so that a worse
  // detour shows.
  EXPECT_LE(summary.mean_path_ratio, 2.0) << summary.text();
}

TEST_F(RoomNavigation, AGoalIsReachedWithinARadiusInMetres) {
  // One trial, run three times (the robot's noise is seeded, so it stops at the same pose): its
  // final error is the true distance from where it stopped to the goal, and it counts as
  // reached exactly when that is within the radius, whatever the map's spacing.
  const Trial trial{{2.55, 1.15, 1.0, deg_to_rad(150.0), 0.0, 0.0},
                    {2.3, 2.9, 1.0, deg_to_rad(-60.0), 0.0, 0.0}};
  const TrialScene scene{map().world, *map().renderer, sim::RobotParams{}};
  const TrialOutcome wide = run_trials({trial}, scene, setup(), 10.0).front();
  ASSERT_TRUE(wide.stopped_at_goal);
  EXPECT_TRUE(wide.reached);
  EXPECT_DOUBLE_EQ(wide.final_error_m,
                   std::hypot(wide.end.x_m - trial.goal.x_m, wide.end.y_m - trial.goal.y_m));
  ASSERT_GT(wide.final_error_m, 0.002);
  const TrialOutcome just_outside =
      run_trials({trial}, scene, setup(), wide.final_error_m - 0.001).front();
  EXPECT_DOUBLE_EQ(just_outside.final_error_m, wide.final_error_m);
  EXPECT_FALSE(just_outside.reached);
  EXPECT_TRUE(run_trials({trial}, scene, setup(), wide.final_error_m + 0.001).front().reached);
  // The default radius is 0.3 m (navigation.yaml's trials.goal_radius_m).
  EXPECT_DOUBLE_EQ(TrialParams{}.goal_radius_m, 0.3);
}

// The robot on the grid's stored images: turning rolls the panorama, a step goes to the next
// grid image.
TEST_F(RoomNavigation, GridWorldTurnsByRollingAndStepsToTheNearestImage) {
  sim::RobotParams exact;
  exact.turn_noise_deg = 0.0;
  const int first = nearest_place(1.2, 1.0);
  const CameraPose at = map().grid[first].pose;
  GridDatabaseWorld world(grid_images(), {at.x_m + 0.05, at.y_m - 0.05, 0.0}, exact);
  EXPECT_EQ(world.current(), static_cast<std::size_t>(first));
  EXPECT_NEAR(world.spacing_m(), kRoomGridSpacing_m, 1e-9);
  // Heading 0 where the image was taken at 20°: 10 columns of 2° to the right. The renderer
  // guarantees render(θ + k·2π/W) == roll(render(θ), k).
  const cv::Mat expected = map().renderer->render({at.x_m, at.y_m, at.z_m, 0.0, 0.0, 0.0});
  EXPECT_EQ(cv::norm(world.view(0), expected, cv::NORM_INF), 0.0);
  // A 15 cm step along +x still goes to the next grid image, 30 cm on.
  EXPECT_NEAR(world.move(0.0, 0.15), kRoomGridSpacing_m, 1e-9);
  EXPECT_NEAR(world.truth().x_m, at.x_m + kRoomGridSpacing_m, 1e-9);
  EXPECT_NEAR(world.truth().y_m, at.y_m, 1e-9);
  // A quarter turn to the left, then a step: one row up.
  EXPECT_NEAR(world.move(kPi / 2, 0.15), kRoomGridSpacing_m, 1e-9);
  EXPECT_NEAR(world.truth().heading_rad, kPi / 2, 1e-9);
  EXPECT_NEAR(world.truth().x_m, at.x_m + kRoomGridSpacing_m, 1e-9);
  EXPECT_NEAR(world.truth().y_m, at.y_m + kRoomGridSpacing_m, 1e-9);
  // Off the grid's edge: blocked. The first image lies on the grid's lower edge, with no
  // image below it or to its left (furniture).
  GridDatabaseWorld corner(grid_images(), {at.x_m, at.y_m, deg_to_rad(-135.0)}, exact);
  EXPECT_EQ(corner.move(0.0, 0.3), 0.0);
  EXPECT_EQ(corner.current(), static_cast<std::size_t>(first));
}

TEST_F(RoomNavigation, NavigationOnARenderedGridReachesItsGoal) {
  const int goal = nearest_place(2.7, 3.1);
  const int start = nearest_place(1.5, 1.0);
  const CameraPose& start_pose = map().grid[start].pose;
  GridDatabaseWorld world(grid_images(), {start_pose.x_m, start_pose.y_m, deg_to_rad(-100.0)},
                          sim::RobotParams{});
  const GoalRun run =
      navigation::navigate_to_image(world, map().grid[goal].panorama, "goal", setup());
  EXPECT_EQ(static_cast<int>(run.goal.place), goal);
  ASSERT_TRUE(run.result.reached) << run.result.steps.size() << " steps";
  const CameraPose& goal_pose = map().grid[goal].pose;
  EXPECT_LT(std::hypot(world.truth().x_m - goal_pose.x_m, world.truth().y_m - goal_pose.y_m),
            0.5 * kRoomGridSpacing_m);
  const double straight_m =
      std::hypot(goal_pose.x_m - start_pose.x_m, goal_pose.y_m - start_pose.y_m);
  EXPECT_LT(run.result.path_length_m, 1.5 * straight_m);
}

// A value set in code is refused by random_trials as the YAML loader refuses it in
// navigation.yaml, naming the key (TrialParams::check).
TEST_F(RoomNavigation, TrialParamsOutOfRangeAreRefusedNamingTheKey) {
  TrialParams params;
  params.goal_radius_m = 0.0;
  try {
    random_trials(map().world, {Eigen::Vector2d::Zero()}, kRoomGridSpacing_m, 0.15, 1.0, params);
    FAIL() << "a goal radius of 0 was accepted";
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find("trials.goal_radius_m"), std::string::npos);
  }
}

}  // namespace
}  // namespace omninav::evaluation
