#include "omninav/navigation/navigator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::navigation {
namespace {

constexpr int kEscapeSteps = 3;

// What homing compares its first view with: a goal infinitely far.
constexpr GoalCue kNoCue{std::numeric_limits<double>::infinity(), 0.0, true};

// The turn from the planned direction of the `sidestep`th try after a block (0: none), in the
// unit of `step`: left by one step, right by one, left by two, right by two, ... (sidesteps
// and escapes)
double sidestep_turn(int sidestep, double step) {
  return (sidestep % 2 == 1 ? 1.0 : -1.0) * ((sidestep + 1) / 2) * step;
}

// Drops the link from `place` to its next place from `plan`'s graph and plans again from the
// goal; keeps the new plan when `place` still reaches the goal (returns true), else leaves
// `plan` as it was.
bool replan_without_link(const std::vector<PlaceNode>& places, int place, RoutePlan& plan) {
  const int next = plan.next[place];
  if (next < 0) return false;
  std::vector<Edge> edges;
  for (const Edge& edge : plan.edges) {
    if (edge != Edge(place, next) && edge != Edge(next, place)) edges.push_back(edge);
  }
  RoutePlan replanned = plan_to_goal(places, edges, plan.goal);
  if (!replanned.reaches_goal(place)) return false;
  plan = std::move(replanned);
  return true;
}

// The place of a step's match, -1 when nothing was recognised.
int place_of(const NavigationStep& step) {
  return step.match ? static_cast<int>(step.match->place) : -1;
}

// Where the localiser puts the robot between places on the lattice, when it can tell (the best
// places' positions weighted by similarity, memory::PositionEstimate).
std::optional<Eigen::Vector2d> lattice_position(const memory::Localisation& localisation) {
  if (!localisation.position || localisation.position->frame != memory::PositionFrame::kLattice)
    return std::nullopt;
  return Eigen::Vector2d(localisation.position->interpolated_x,
                         localisation.position->interpolated_y);
}

}  // namespace

void load_navigator_params(const ConfigReader& section, NavigatorParams& params) {
  section.read("step_m", params.step_m, 0.01, 5.0);
  section.read("max_steps", params.max_steps, 1, 100000);
  section.read("goal_similarity", params.goal_similarity, 0.0, 1000.0);
  section.read("goal_confirmations", params.goal_confirmations, 1, 100);
  section.read("unstick_turn_deg", params.unstick_turn_deg, 0.0, 180.0);
  section.read("look_ahead_links", params.look_ahead_links, 0, 1000);
  section.read("look_ahead_tolerance_spacings", params.look_ahead_tolerance_spacings, 0.0, 10.0);
  section.read("sidesteps", params.sidesteps, 0, 16);
  section.read("sidestep_deg", params.sidestep_deg, 1.0, 90.0);
  section.read("loop_entries", params.loop_entries, 0, 100000);
  section.read("home_on_goal_image", params.home_on_goal_image);
  section.read("homing_step_m", params.homing_step_m, 0.01, 5.0);
  section.read("homing_stop_m", params.homing_stop_m, 0.0, 5.0);
  section.read("homing_max_steps", params.homing_max_steps, 0, 100000);
  // The last sidestep turns farthest: past 180° it would repeat an earlier direction.
  const double widest_deg = std::abs(sidestep_turn(params.sidesteps, params.sidestep_deg));
  if (widest_deg > 180.0) {
    std::ostringstream message;
    message << section.source_name() << ": keys 'navigator.sidesteps' (" << params.sidesteps
            << ") and 'navigator.sidestep_deg' (" << params.sidestep_deg
            << ") turn the last sidestep " << widest_deg
            << " degrees from the plan, more than 180: give fewer sidesteps or smaller ones";
    throw ConfigError(message.str());
  }
}

NavigationResult navigate(NavigationWorld& world, const std::vector<PlaceNode>& places,
                          const RoutePlan& initial_plan, const PanoramaLocaliser& localise,
                          const NavigatorParams& params, const GoalHoming& homing) {
  NavigationResult result;
  RoutePlan plan = initial_plan;
  int expected = -1;  // the place the plan said we would reach next
  int goal_matches = 0;
  // Blocked: first the sidesteps (params.sidesteps), counted here; then the link is dropped and
  // the plan made again; when no route is left round it, escape: drive a few steps at an angle
  // from the planned direction, then follow the plan again. Blocked again while escaping, the
  // robot tries the next escape turn: the other side, then wider (a robot in a corner between
  // two boxes is blocked both ways at unstick_turn_deg), round to the first after 180°.
  int sidestep = 0;
  int escape_steps_left = 0;
  int escape_turn = 0;
  // Links the robot could not drive along: the look-ahead keeps its straight lines away.
  std::vector<Edge> blocked;
  const double look_ahead_tolerance_m =
      params.look_ahead_links > 1 ? params.look_ahead_tolerance_spacings * lattice_spacing(places)
                                  : 0.0;
  std::vector<int> entries(places.size(), 0);  // times each place was entered (loops)
  // Homing on the goal image: the cue of the last view, once the goal place was recognised.
  std::optional<GoalCue> homing_from;
  for (int index = 0; index < params.max_steps; ++index) {
    NavigationStep step;
    step.index = index;
    step.truth = world.truth();
    const cv::Mat view = world.view(index);
    const memory::Localisation localisation = localise(view);
    if (!localisation.best.empty()) step.match = localisation.best.front();
    const int place = place_of(step);
    const int previous = result.steps.empty() ? -1 : place_of(result.steps.back());
    if (place >= 0) {
      step.heading_estimate_rad =
          wrap_angle(places[place].heading_rad + step.match->relative_heading_rad);
    }

    if (!homing_from) {
      if (place < 0) {  // nothing recognised (an empty candidate set): go on straight ahead
        result.path_length_m += world.move(0.0, params.step_m);
        result.steps.push_back(step);
        continue;
      }
      // A jump: neither where we were, nor where we were heading, nor next to either.
      if (expected >= 0) {
        const Eigen::Vector2d here = places[place].position_m;
        const double near_m = 2.0 * params.step_m + 1e-9;
        step.jump = (here - places[expected].position_m).norm() > near_m &&
                    (previous < 0 || (here - places[previous].position_m).norm() > near_m);
        result.jumps += step.jump ? 1 : 0;
      }
      if (place == plan.goal && step.match->similarity >= params.goal_similarity) {
        if (++goal_matches >= params.goal_confirmations) {
          if (!homing || !params.home_on_goal_image || params.homing_max_steps == 0) {
            result.steps.push_back(step);
            result.reached = true;
            return result;
          }
          // The goal place is recognised: from here on, home on the goal image (no view to
          // compare this first one with yet).
          homing_from = kNoCue;
          sidestep = 0;
        }
      } else {
        goal_matches = 0;
      }
    }

    if (homing_from) {
      // Step towards the goal image, as far as it seems to be (up to a homing step), while it
      // seems farther than homing_stop_m and nearer than at the last view; stop when it seems
      // farther (the last step passed the goal), when the phases show no displacement (at the
      // goal), or when the homing budget is spent.
      const GoalCue cue = homing(view);
      if (cue.distance_m <= params.homing_stop_m || cue.distance_m >= homing_from->distance_m ||
          !cue.valid || result.homing_steps >= params.homing_max_steps) {
        result.steps.push_back(step);
        result.reached = true;
        return result;
      }
      step.turn_rad = cue.bearing_rad + sidestep_turn(sidestep, deg_to_rad(params.sidestep_deg));
      const double distance_m = std::min(cue.distance_m, params.homing_step_m);
      const double driven = world.move(step.turn_rad, distance_m);
      result.path_length_m += driven;
      ++result.homing_steps;
      result.steps.push_back(step);
      if (driven >= 0.5 * distance_m) {
        // After a sidestep the goal may well seem farther: the next view starts afresh.
        homing_from = sidestep == 0 ? cue : kNoCue;
        sidestep = 0;
      } else if (sidestep < params.sidesteps) {
        // Blocked: the goal lies beyond a corner of furniture. Sidestep as on the way, and
        // judge the next view against the last one that moved (this one saw the same).
        ++sidestep;
        ++result.sidesteps;
      } else {
        // Blocked every way: this is as near as the robot gets.
        result.reached = true;
        return result;
      }
      continue;
    }

    // Going round in circles: entering the same place again and again. Its direction leads
    // into places whose directions lead back; plan again without the link it follows.
    if (place != previous && params.loop_entries > 0 && ++entries[place] >= params.loop_entries &&
        place != plan.goal) {
      entries[place] = 0;
      if (replan_without_link(places, place, plan)) ++result.loops;
    }

    // Turn to the place's assigned direction, measured against the place's own heading: the
    // robot's heading relative to the place is what the image tells, whatever the lattice.
    double direction_in_place = plan.direction_in_place_rad[place];
    if (place == plan.goal || !plan.reaches_goal(place)) {
      direction_in_place = step.match->relative_heading_rad;
    } else if (params.look_ahead_links > 0 && lattice_position(localisation) && sidestep == 0) {
      // Sidesteps turn from the place's own direction instead: the line ahead led into the
      // obstacle, and turning from the place's next link measured better (docs/navigation.md).
      const int target = look_ahead_place(places, plan, place, params.look_ahead_links,
                                          look_ahead_tolerance_m, blocked);
      const Eigen::Vector2d to = places[target].position_m - *lattice_position(localisation);
      if (to.norm() > 1e-9) {
        direction_in_place =
            signed_difference(std::atan2(to.y(), to.x()), places[place].heading_rad);
      }
    }
    const bool escaping = escape_steps_left > 0;
    if (escaping) {
      direction_in_place += sidestep_turn(escape_turn, deg_to_rad(params.unstick_turn_deg));
      --escape_steps_left;
    } else {
      direction_in_place += sidestep_turn(sidestep, deg_to_rad(params.sidestep_deg));
      result.sidesteps += sidestep > 0 ? 1 : 0;
    }
    step.turn_rad = signed_difference(direction_in_place, step.match->relative_heading_rad);
    const double driven = world.move(step.turn_rad, params.step_m);
    if (driven >= 0.5 * params.step_m) {
      sidestep = 0;
    } else if (!escaping && sidestep < params.sidesteps) {
      ++sidestep;
    } else {
      sidestep = 0;
      if (!escaping && plan.next[place] >= 0) blocked.emplace_back(place, plan.next[place]);
      if (escaping || !replan_without_link(places, place, plan)) {
        escape_turn = escaping ? escape_turn + 1 : 1;
        if (std::abs(sidestep_turn(escape_turn, params.unstick_turn_deg)) > 180.0) escape_turn = 1;
        escape_steps_left = kEscapeSteps;
      } else {
        ++result.replans;
      }
    }
    result.path_length_m += driven;
    expected = plan.next[place] >= 0 ? plan.next[place] : place;
    result.steps.push_back(step);
  }
  // The budget ran out while homing: the goal place was recognised, as the paper's robot asks.
  result.reached = homing_from.has_value();
  return result;
}

}  // namespace omninav::navigation
