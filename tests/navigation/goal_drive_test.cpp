// The navigator a view at a time (goal_drive.hpp) as a caller drives it: a virtual robot in the
// built-in room (tests/support/room_navigation_map.hpp) shown each view, moved by each command,
// judged against the renderer's poses; and the calls it refuses out of order.
#include "omninav/navigation/goal_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>
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

}  // namespace
}  // namespace omninav::navigation
