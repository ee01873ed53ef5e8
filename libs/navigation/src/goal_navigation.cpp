#include "omninav/navigation/goal_navigation.hpp"

#include "omninav/navigation/memory_places.hpp"

namespace omninav::navigation {

GoalRun navigate_to_image(NavigationWorld& world, const cv::Mat& goal_image,
                          const std::string& what, const GoalNavigationSetup& setup) {
  GoalRun run;
  run.goal = match_image(setup.localise, goal_image, setup.match_limit, what);
  run.plan = plan_route(setup, static_cast<int>(run.goal.place));
  run.result = navigate(world, setup.places, run.plan,
                        plan_over_other_links(setup, static_cast<int>(run.goal.place)),
                        setup.localise, setup.navigator, goal_homing(goal_image, setup.homing),
                        setup.recognition_limit, setup.place_recognition_limits);
  return run;
}

}  // namespace omninav::navigation
