#include "omninav/navigation/goal_navigation.hpp"

#include "omninav/navigation/memory_places.hpp"

namespace omninav::navigation {

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
