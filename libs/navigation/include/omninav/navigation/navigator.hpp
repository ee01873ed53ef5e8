#pragma once
// The reactive navigator of 001_5bb151a4e28490b4.txt §3.5: grab a panorama, recognise the
// place, measure the robot's heading against the place's image, turn to the direction the
// route plan assigned to that place, step, repeat. It never uses the robot's true pose: the
// plan, the memory and the images are all it knows. When localisation jumps to a place other
// than the one expected (the paper's O4/O5 case: the lattice is distorted), it simply follows
// the new place's direction; the jump is recorded.

#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "omninav/core/pose.hpp"
#include "omninav/navigation/route_planner.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/virtual_robot.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::navigation {

// What a localiser says about a panorama: the best place, how sure it is, and the robot's
// heading relative to that place's stored heading (counter-clockwise positive).
struct PlaceMatch {
  int place = -1;
  double similarity = 0.0;  // 0..1000 (001 Eq. 3)
  double heading_in_place_rad = 0.0;
};

using Localiser = std::function<PlaceMatch(const cv::Mat& panorama)>;

struct NavigatorParams {
  double step_m = 0.15;            // distance driven between two images
  int max_steps = 300;             // budget; the run fails when it is spent
  double goal_similarity = 0.0;    // the goal place must match with at least this similarity
  int goal_confirmations = 1;      // consecutive goal matches needed to stop
  double unstick_turn_deg = 60.0;  // turn tried when the robot did not move (blocked)
};

// Reads the `navigator:` section of navigation.yaml.
void load_navigator_params(const ConfigReader& section, NavigatorParams& params);

struct NavigationStep {
  int index = 0;
  CameraPose truth;  // where the robot really was (evaluation only)
  PlaceMatch match;
  double heading_estimate_rad = 0.0;  // in the lattice frame: place heading + heading in place
  double turn_rad = 0.0;              // the turn commanded
  bool jump = false;                  // matched neither the expected place nor its neighbours
};

struct NavigationResult {
  bool reached = false;
  std::vector<NavigationStep> steps;
  double path_length_m = 0.0;  // distance the robot drove
  int jumps = 0;
};

NavigationResult navigate(sim::VirtualRobot& robot, const sim::Renderer& renderer,
                          const std::vector<PlaceNode>& places, const RoutePlan& plan,
                          const Localiser& localise, const NavigatorParams& params);

}  // namespace omninav::navigation
