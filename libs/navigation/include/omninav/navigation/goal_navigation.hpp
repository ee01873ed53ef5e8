#pragma once
// Navigating to a goal image: the goal image matched to a place, the route planned to it over
// the lattice, the robot driven there and homing on the goal image at the end. The same for a
// robot in a rendered world, on a grid of stored images or in an evaluation's trials.

#include <limits>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "omninav/navigation/homing.hpp"
#include "omninav/navigation/navigator.hpp"
#include "omninav/navigation/route_planner.hpp"

namespace omninav::navigation {

// What navigating to a goal image needs besides the world and the goal, the same for every goal
// on one map (memory_places.hpp makes each from the map).
struct GoalNavigationSetup {
  std::vector<PlaceNode> places;  // places_from_memory
  PanoramaLocaliser localise;     // memory_localiser, or a stand-in
  // The goal image must match a place within this mean dissimilarity per value (match_limit).
  double match_limit = std::numeric_limits<double>::infinity();
  HomingScale homing;  // homing_scale
  RouteParams route;
  NavigatorParams navigator;
  // The robot's views must match a place within this, or it finds itself lost
  // (recognition_limit, NavigatorParams::lost_views).
  double recognition_limit = std::numeric_limits<double>::infinity();
  // The links plans run over (motion_links) when they do not rest on the lattice; empty: the
  // lattice neighbours (RouteParams::links).
  std::vector<MeasuredLink> links;
  // Each place's own limit instead (place_recognition_limits); empty: recognition_limit.
  std::vector<double> place_recognition_limits;
  // The motions when plans run over the lattice, for a stalled robot to switch to
  // (NavigatorParams::stall_other_links; plan_over_other_links); empty: none.
  std::vector<MeasuredLink> other_links;
};

// One navigation: the goal image's place, the plan to it and the run.
struct GoalRun {
  memory::PlaceMatch goal;  // the goal image's place
  RoutePlan plan;
  NavigationResult result;
};

// Matches `goal_image` (named `what` in messages) to a place (match_image with
// setup.match_limit: InputError when it matches none), plans to it (plan_route) and drives
// `world`'s robot there, homing on the goal image at the end.
GoalRun navigate_to_image(NavigationWorld& world, const cv::Mat& goal_image,
                          const std::string& what, const GoalNavigationSetup& setup);

}  // namespace omninav::navigation
