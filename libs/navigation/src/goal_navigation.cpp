#include "omninav/navigation/goal_navigation.hpp"

#include <algorithm>
#include <optional>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/navigation/goal_drive.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "omninav/signature/phase_heading.hpp"

namespace omninav::navigation {

void place_dissimilarities(const GoalNavigationSetup& setup, const signature::Signature& view,
                           std::span<double> out) {
  for (std::size_t p = 0; p < setup.signatures.size(); ++p) {
    out[p] = signature::dissimilarity(view, setup.signatures[p], -1, setup.weights) /
             static_cast<double>(view.size());
  }
}

namespace {

// The goal image (signature `goal`, its dissimilarity per value to every place) as a match of
// `place`, its heading from the phases as localise gives it.
memory::PlaceMatch goal_match(const GoalNavigationSetup& setup, const signature::Signature& goal,
                              const std::vector<double>& dissimilarity, int place) {
  memory::PlaceMatch match;
  match.place = static_cast<memory::PlaceIndex>(place);
  match.dissimilarity_per_value = dissimilarity[place];
  match.dissimilarity = dissimilarity[place] * static_cast<double>(goal.size());
  match.similarity = signature::rescale_similarities(dissimilarity)[place];
  const signature::PhaseHeading heading =
      signature::relative_heading(setup.signatures[place], goal);
  match.relative_heading_rad = heading.turn_rad;
  match.heading_confidence = heading.confidence;
  match.heading_rad = wrap_angle(setup.places[place].heading_rad + heading.turn_rad);
  return match;
}

}  // namespace

memory::PlaceMatch recognise_goal(const GoalNavigationSetup& setup, const cv::Mat& goal_image,
                                  const std::string& what) {
  match_image(setup.localise, goal_image, setup.match_limit, what);  // refuses a foreign image
  const signature::Signature goal = setup.signature_of(goal_image);
  std::vector<double> dissimilarity(setup.signatures.size());
  place_dissimilarities(setup, goal, dissimilarity);
  const auto least = std::min_element(dissimilarity.begin(), dissimilarity.end());
  const int by_signature = static_cast<int>(least - dissimilarity.begin());
  PlaceSteering warping(setup.snapshots);
  const std::optional<compass::MinWarpingResult> signature_match =
      warping.match(by_signature, goal_image, what);
  if (!signature_match) return goal_match(setup, goal, dissimilarity, by_signature);
  int place = by_signature;
  double least_cost = signature_match->cost;
  const double shortlist = *least + setup.goal_shortlist_ratio * setup.link_dissimilarity;
  for (std::size_t p = 0; p < dissimilarity.size(); ++p) {
    if (static_cast<int>(p) == by_signature || dissimilarity[p] > shortlist) continue;
    const std::optional<compass::MinWarpingResult> match =
        warping.match(static_cast<int>(p), goal_image, what);
    if (match && match->cost < least_cost) {
      least_cost = match->cost;
      place = static_cast<int>(p);
    }
  }
  return goal_match(setup, goal, dissimilarity, place);
}

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
  run.goal = recognise_goal(setup, goal_image, what);
  const int goal = static_cast<int>(run.goal.place);
  run.plan = plan_to_goal(setup.places, setup.links, goal);
  run.result = navigate(world, setup, goal, goal_homing(goal_image, setup.homing));
  return run;
}

}  // namespace omninav::navigation
