#include "omninav/navigation/navigator.hpp"

#include "omninav/core/config.hpp"
#include "omninav/core/param_check.hpp"

namespace omninav::navigation {

const char* phase_name(NavigationPhase phase) {
  switch (phase) {
    case NavigationPhase::kFollowingRoute:
      return "route";
    case NavigationPhase::kHoming:
      return "homing";
  }
  return "?";
}

void NavigatorParams::check() const {
  check_range("navigator.step_m", step_m, 0.01, 5.0);
  check_range("navigator.max_steps", max_steps, 1, 100000);
  check_range("navigator.homing_step_m", homing_step_m, 0.01, 5.0);
  check_range("navigator.homing_stop_m", homing_stop_m, 0.0, 5.0);
  check_range("navigator.homing_step_spacings", homing_step_spacings, 0.0, 10.0);
  check_range("navigator.homing_stop_spacings", homing_stop_spacings, 0.0, 10.0);
  check_range("navigator.homing_max_steps", homing_max_steps, 0, 100000);
}

void load_navigator_params(const ConfigReader& section, NavigatorParams& params) {
  section.read("step_m", params.step_m);
  section.read("max_steps", params.max_steps);
  section.read("home_on_goal_image", params.home_on_goal_image);
  section.read("homing_step_m", params.homing_step_m);
  section.read("homing_stop_m", params.homing_stop_m);
  section.read("homing_step_spacings", params.homing_step_spacings);
  section.read("homing_stop_spacings", params.homing_stop_spacings);
  section.read("homing_max_steps", params.homing_max_steps);
  check_loaded(section.source_name(), [&] { params.check(); });
}

}  // namespace omninav::navigation
