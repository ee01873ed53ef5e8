#include "omninav/navigation/goal_navigation.hpp"

#include <vector>

#include "omninav/navigation/goal_drive.hpp"
#include "omninav/navigation/memory_places.hpp"

namespace omninav::navigation {

NavigationResult navigate(NavigationWorld& world, const GoalNavigationSetup& setup, int goal,
                          const GoalHoming& homing) {
  GoalDrive drive(setup, goal, homing);
  std::vector<CameraPose> truth;  // for the step log only: the drive never sees it
  for (int index = 0; !drive.finished(); ++index) {
    truth.push_back(world.truth());
    const DriveCommand command = drive.step(world.view(index));
    if (command.moves) drive.moved(world.move(command.turn_rad, command.distance_m));
  }
  NavigationResult result = drive.result();
  for (NavigationStep& step : result.steps) step.truth = truth[step.index];
  return result;
}

GoalRun navigate_to_image(NavigationWorld& world, const cv::Mat& goal_image,
                          const std::string& what, const GoalNavigationSetup& setup) {
  GoalRun run;
  run.goal = match_image(setup.localise, goal_image, setup.match_limit, what);
  const int goal = static_cast<int>(run.goal.place);
  run.plan = plan_to_goal(setup.places, setup.links, goal);
  run.result = navigate(world, setup, goal, goal_homing(goal_image, setup.homing));
  return run;
}

}  // namespace omninav::navigation
