#pragma once
// Navigating to a goal image: the goal image's place recognised, the route planned to it over
// the confirmed links, the robot driven there by the belief over places and homing on the goal
// image at the end. The same for a robot in a rendered world, on a grid of stored images or in
// an evaluation's trials.

#include <functional>
#include <limits>
#include <opencv2/core.hpp>
#include <span>
#include <string>
#include <vector>

#include "omninav/lattice/confirmed_links.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/navigation/homing.hpp"
#include "omninav/navigation/navigator.hpp"
#include "omninav/navigation/place_belief.hpp"
#include "omninav/navigation/place_steering.hpp"
#include "omninav/navigation/route_planner.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::navigation {

// How the goal image is localised: the memory's hierarchical localisation of the panorama
// (memory_localiser, memory_places.hpp) or a stand-in.
using PanoramaLocaliser = std::function<memory::Localisation(const cv::Mat& panorama)>;

// What navigating to a goal image needs besides the world and the goal, the same for every goal
// on one map (memory_places.hpp, goal_navigation_setup, makes each from the map).
struct GoalNavigationSetup {
  std::vector<PlaceNode> places;  // places_from_memory: each place's heading
  PanoramaLocaliser localise;     // matches the goal image (memory_localiser)
  // The goal image must match a place within this mean dissimilarity per value (match_limit).
  double match_limit = std::numeric_limits<double>::infinity();
  // The goal's shortlist (recognise_goal): places within this many link_dissimilarity of the
  // goal image's best (RouteParams::goal_shortlist_ratio).
  double goal_shortlist_ratio = RouteParams{}.goal_shortlist_ratio;
  HomingScale homing;  // homing_scale
  NavigatorParams navigator;
  std::vector<MeasuredLink> links;  // confirmed_links: what the plan and the belief run over
  // Every place's signature, how a view's is made and how the two are compared (Eq. 6's
  // weights), and τ's unit: the median dissimilarity per value over the links.
  std::vector<signature::Signature> signatures;
  signature::ComponentWeights weights;
  std::function<signature::Signature(const cv::Mat&)> signature_of;
  double link_dissimilarity = 1.0;
  BeliefParams belief;
  // The places' thumbnails the robot steers by (place_steering.hpp); none: it steers by the
  // plan's directions alone.
  std::shared_ptr<const PlaceSnapshots> snapshots;
};

// The view's mean dissimilarity per value (Eq. 6 with the map's weights) to every place of
// `setup`, into `out` (one per place): what the belief weighs a view by.
void place_dissimilarities(const GoalNavigationSetup& setup, const signature::Signature& view,
                           std::span<double> out);

// The goal image's place, coarse to fine. The goal image must match a place (match_image with
// setup.match_limit: InputError naming `what` when it matches none). The places whose
// dissimilarity to it (place_dissimilarities) is within setup.goal_shortlist_ratio ×
// setup.link_dissimilarity of the least form the shortlist, and min-warping (place_steering.hpp)
// compares each one's thumbnail with the goal image: the lowest cost is the goal's place. The
// Fourier magnitudes (§2.2) keep little of an image, and where places look alike (desks in
// rows, grass seen from 10 cm) the goal image's best place by them is often a look-alike metres
// away; min-warping compares every column, allowing for the move between the two. Without
// thumbnails, or when the signature's best place has none min-warping can match, that place.
memory::PlaceMatch recognise_goal(const GoalNavigationSetup& setup, const cv::Mat& goal_image,
                                  const std::string& what);

// Drives `world`'s robot to place `goal` (navigator.hpp), then homes on the goal image with
// `homing` (none: stops on reaching the goal's place): a loop of view, GoalDrive::step, move,
// GoalDrive::moved (goal_drive.hpp), the steps' truth read from the world for the log. Throws
// UsageError for a goal that names no place or a setup without places.
NavigationResult navigate(NavigationWorld& world, const GoalNavigationSetup& setup, int goal,
                          const GoalHoming& homing = {});

// One navigation: the goal image's place, the plan to it and the run.
struct GoalRun {
  memory::PlaceMatch goal;  // the goal image's place
  RoutePlan plan;
  NavigationResult result;
};

// Recognises the place of `goal_image` (named `what` in messages; recognise_goal), plans to it
// over setup.links and drives `world`'s robot there, homing on the goal image at the end.
GoalRun navigate_to_image(NavigationWorld& world, const cv::Mat& goal_image,
                          const std::string& what, const GoalNavigationSetup& setup);

}  // namespace omninav::navigation
