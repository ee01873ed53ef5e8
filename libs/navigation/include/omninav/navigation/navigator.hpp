#pragma once
// The navigator (Menegatti et al. 2004, §3.5, with a belief over places): each view of the
// robot updates the belief over the map's places (place_belief.hpp); the robot acts on the most
// probable place that has a route: it turns towards that place's next place on the plan
// (route_planner.hpp, over the confirmed links of confirmed_links.hpp) by the next place's image
// (min-warping's home vector, place_steering.hpp; without images, to the plan's direction at
// the place, its heading measured against the place's image by the phases, Eq. 1) and steps.
// The motion it made carries the belief along the links. Once the belief is on the goal's place
// it homes on the goal image (homing.hpp). It never reads the robot's true pose: the map, the
// plan and the images are all it knows.
//
// The parts: belief (place_belief.hpp), plan (route_planner.hpp), motion (goal_drive.hpp, one
// view at a time: turn, step, home; place_steering.hpp) and recovery, which is two rules about
// links, each learnt by driving:
//   - blocked (the robot drove less than half a step): it turns aside, 45° more each time,
//     alternately left and right, until it has tried every direction; then the link it was
//     following is dropped and the plan made again (not while lost);
//   - a link not followed: the robot drove three times a link's length (and a step) since the
//     belief last came to a place nearer the goal without getting nearer: that link is dropped
//     and the plan made again (a revisit whose direction misleads, a passage too narrow).

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "omninav/core/pose.hpp"
#include "omninav/memory/localisation.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::navigation {

struct NavigatorParams {
  double step_m = 0.15;  // distance driven between two images
  int max_steps = 300;   // budget; the run fails when it is spent
  // Beyond §3.5 (homing.hpp): once the belief is on the goal's place, the robot steps towards
  // the goal image while the goal seems nearer than at the last view and farther than
  // homing_stop_m, instead of stopping at once.
  bool home_on_goal_image = true;
  double homing_step_m = 0.1;   // longest homing step (a step goes as far as the goal seems)
  double homing_stop_m = 0.15;  // the goal seeming this near ends homing
  // The same two in spacings of the map (> 0: goal_navigation_setup sets the metres above from
  // the map's own spacing, memory_places.hpp map_spacing; 0: the metres as given).
  double homing_step_spacings = 0.333;
  double homing_stop_spacings = 0.5;
  int homing_max_steps = 8;  // homing steps at most (they count against max_steps too)

  // The ranges of navigation.yaml's navigator section. Throws UsageError naming the key
  // (core/param_check.hpp); the loader and goal_navigation_setup (memory_places.hpp) call it.
  void check() const;
};

// Reads the `navigator:` section of navigation.yaml.
void load_navigator_params(const ConfigReader& section, NavigatorParams& params);

// What the navigator acts on: a robot somewhere that shows what it sees and moves when told.
// The loop is the same whether the world is rendered or a grid of stored images (the
// evaluation layer's robot worlds) or a stand-in.
class NavigationWorld {
 public:
  virtual ~NavigationWorld() = default;
  // The panorama the robot sees now; `step` numbers the views (it seeds sensor noise).
  virtual cv::Mat view(int step) = 0;
  // Turns by `turn_rad` (counter-clockwise positive), then drives up to `distance_m` forward.
  // Returns the distance actually driven (0 when blocked).
  virtual double move(double turn_rad, double distance_m) = 0;
  // Where the robot really is: for evaluation and the step log only, the loop never reads it.
  virtual CameraPose truth() const = 0;
};

// What the navigator was doing at a step.
enum class NavigationPhase {
  kFollowingRoute,  // acting on the belief's place
  kHoming,          // homing on the goal image
};

// "route", "homing" (steps.csv).
const char* phase_name(NavigationPhase phase);

struct NavigationStep {
  int index = 0;
  CameraPose truth;  // where the robot really was (evaluation only)
  // The place the robot acted on, the view's dissimilarity per value to it, the robot's heading
  // relative to it (phases) and, as `similarity`, its probability × 1000.
  std::optional<memory::PlaceMatch> match;
  double heading_estimate_rad = 0.0;  // in the map's frame: place heading + heading in place
  double turn_rad = 0.0;              // the turn commanded
  bool jump = false;                  // the place acted on is neither the last one nor linked to it
  bool recognised = false;            // the belief is confident (PlaceBelief::lost is false)
  NavigationPhase phase = NavigationPhase::kFollowingRoute;
  bool lost = false;  // the belief is spread (PlaceBelief::lost)
};

struct NavigationResult {
  bool reached = false;
  std::vector<NavigationStep> steps;
  double path_length_m = 0.0;  // distance the robot drove
  int jumps = 0;
  int sidesteps = 0;  // moves turned aside after a block
  int replans = 0;    // times the plan was made again: a link dropped (blocked, not followed), or
                      // the dropped links restored (they cut off the belief's place)
  int homing_steps = 0;  // steps taken towards the goal image after the belief reached its place
  int lost_events = 0;   // times the belief became spread (PlaceBelief::lost)
};

}  // namespace omninav::navigation
