// The navigator a view at a time (goal_drive.hpp) as a caller drives it: a virtual robot in the
// built-in room (tests/support/room_navigation_map.hpp) shown each view, moved by each command,
// judged against the renderer's poses; and the calls it refuses out of order.
#include "omninav/navigation/goal_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/sim/virtual_robot.hpp"
#include "support/room_navigation_map.hpp"

namespace omninav::navigation {
namespace {

using testing::RoomNavigation;

TEST_F(RoomNavigation, AViewAtATimeDrivesARobotToTheGoalAndRefusesCallsOutOfOrder) {
  // Start and goal of the navigator's short run (tests/evaluation/navigation_trials_test.cpp).
  const CameraPose start{2.55, 1.15, 1.0, deg_to_rad(150.0), 0.0, 0.0};
  const CameraPose goal{2.3, 2.9, 1.0, deg_to_rad(-60.0), 0.0, 0.0};
  const GoalNavigationSetup navigation = setup();
  const cv::Mat goal_image = map().renderer->render(goal);
  GoalDrive drive(navigation, nearest_place(goal.x_m, goal.y_m),
                  goal_homing(goal_image, navigation.homing));
  EXPECT_THROW(drive.moved(0.1), UsageError);  // no command yet
  sim::VirtualRobot robot(map().world, start, sim::RobotParams{});
  double path_m = 0.0;
  int views = 0;
  while (!drive.finished()) {
    const DriveCommand command = drive.step(map().renderer->render(robot.pose()));
    EXPECT_EQ(command.step.index, views++);
    if (!command.moves) break;
    EXPECT_GT(command.distance_m, 0.0);
    if (views == 1) {
      // Before its motion is reported, no other view and no distance that is not one.
      EXPECT_THROW(drive.step(map().renderer->render(robot.pose())), UsageError);
      EXPECT_THROW(drive.moved(std::numeric_limits<double>::quiet_NaN()), InputError);
    }
    const double driven_m = robot.move(command.turn_rad, command.distance_m);
    path_m += driven_m;
    drive.moved(driven_m);
  }
  ASSERT_TRUE(drive.result().reached) << views << " views";
  EXPECT_EQ(static_cast<int>(drive.result().steps.size()), views);
  EXPECT_NEAR(drive.result().path_length_m, path_m, 1e-9);
  // The trials' criterion (trials.goal_radius_m), by the renderer's pose.
  EXPECT_LT(std::hypot(robot.pose().x_m - goal.x_m, robot.pose().y_m - goal.y_m), 0.3);
  EXPECT_THROW(drive.step(map().renderer->render(robot.pose())), UsageError);  // finished
}

TEST_F(RoomNavigation, AGoalThatIsNoPlaceIsRefused) {
  const GoalNavigationSetup navigation = setup();
  EXPECT_THROW(GoalDrive(navigation, -1), UsageError);
  EXPECT_THROW(GoalDrive(navigation, static_cast<int>(navigation.places.size())), UsageError);
}

// The navigator's short run with a belief never confident (all of it would have to lie on one
// place and its neighbours), as where views change within centimetres: the robot never homes by
// the belief, and stops only by the goal image once it acts on the goal's place. `homing` is
// given the goal image's own cue; the result, and how far the robot stopped from the goal.
struct UnsettledRun {
  NavigationResult result;
  double goal_error_m = 0.0;
};
UnsettledRun run_never_confident(const std::function<GoalHoming(GoalHoming)>& homing) {
  BeliefParams never_confident;
  never_confident.confident_share = 1.0;
  const testing::RoomMap& map = RoomNavigation::map();
  const GoalNavigationSetup navigation =
      goal_navigation_setup(map.memory, map.localise, RouteParams{}, NavigatorParams{},
                            LinkParams{}, never_confident, SteeringParams{{}, map.render.geometry});
  const CameraPose start{2.55, 1.15, 1.0, deg_to_rad(150.0), 0.0, 0.0};
  const CameraPose goal{2.3, 2.9, 1.0, deg_to_rad(-60.0), 0.0, 0.0};
  GoalDrive drive(navigation, RoomNavigation::nearest_place(goal.x_m, goal.y_m),
                  homing(goal_homing(map.renderer->render(goal), navigation.homing)));
  sim::VirtualRobot robot(map.world, start, sim::RobotParams{});
  while (!drive.finished()) {
    const DriveCommand command = drive.step(map.renderer->render(robot.pose()));
    if (!command.moves) break;
    drive.moved(robot.move(command.turn_rad, command.distance_m));
  }
  return {drive.result(), std::hypot(robot.pose().x_m - goal.x_m, robot.pose().y_m - goal.y_m)};
}

TEST_F(RoomNavigation, ARobotWhoseBeliefNeverSettlesStopsWhereTheGoalImageSaysTheGoalIs) {
  // The goal image seems near once the robot is near it.
  const UnsettledRun run = run_never_confident([](GoalHoming homing) { return homing; });
  ASSERT_TRUE(run.result.reached) << run.result.steps.size() << " views";
  EXPECT_EQ(run.result.homing_steps, 0);
  EXPECT_LT(run.goal_error_m, 0.3);
}

TEST_F(RoomNavigation, ARobotToWhichTheGoalImageAlwaysSeemsFarStopsOnceItHasCrossedTheGoalTwice) {
  // As in grass seen from 10 cm, the goal image's dissimilarity says "far" even at the goal. The
  // robot steers by the goal image's bearing once it acts on the goal's place, and stops when it
  // has crossed the goal twice: turned about to the bearing, a step towards it leaves the goal
  // behind again.
  const UnsettledRun run = run_never_confident([](GoalHoming homing) {
    return [homing](const cv::Mat& view) {
      GoalCue cue = homing(view);
      cue.distance_m += 10.0;
      return cue;
    };
  });
  ASSERT_TRUE(run.result.reached) << run.result.steps.size() << " views";
  EXPECT_EQ(run.result.homing_steps, 0);
  // Within a step (navigator.step_m) of the goal, and the trials' criterion.
  EXPECT_LT(run.goal_error_m, NavigatorParams{}.step_m + 0.05);
}

TEST_F(RoomNavigation, TheRobotActsOnThePlaceItSeesEvenWhenDroppedLinksCutItOff) {
  // The grid's first row as a corridor: links between its neighbours only, so that dropping
  // the one link from its first place cuts that place off from the goal at the row's far end.
  GoalNavigationSetup navigation = setup();
  const double row_y = map().grid.front().pose.y_m;
  const auto in_row = [&](int place) {
    return std::abs(map().grid[place].pose.y_m - row_y) < 1e-9;
  };
  std::erase_if(navigation.links, [&](const MeasuredLink& link) {
    return !in_row(link.places.first) || !in_row(link.places.second);
  });
  ASSERT_GE(navigation.links.size(), 3u);
  int goal = 0;
  for (std::size_t p = 0; p < map().grid.size(); ++p) {
    if (in_row(static_cast<int>(p)) && map().grid[p].pose.x_m > map().grid[goal].pose.x_m) {
      goal = static_cast<int>(p);
    }
  }
  // A robot whose wheels spin: its odometry reports every command driven, its view is always
  // the first place's. 40 views of 15 cm are the progress rule's three link lengths many times
  // over: the link from the first place is dropped, again and again.
  GoalDrive drive(navigation, goal);
  for (int view = 0; view < 40 && !drive.finished(); ++view) {
    const DriveCommand command = drive.step(map().grid[0].panorama);
    // Acted on as the place it shows, never as a place the belief gives next to nothing
    // because that one still has a route.
    EXPECT_EQ(command.step.match->place, 0u) << "view " << view;
    if (command.moves) drive.moved(command.distance_m);
  }
  // Dropped and restored, more than once.
  EXPECT_GE(drive.result().replans, 2);
}

}  // namespace
}  // namespace omninav::navigation
