#include "omninav/navigation/navigator.hpp"

#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"

namespace omninav::navigation {
namespace {

constexpr int kEscapeSteps = 3;

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

}  // namespace

void load_navigator_params(const ConfigReader& section, NavigatorParams& params) {
  section.read("step_m", params.step_m, 0.01, 5.0);
  section.read("max_steps", params.max_steps, 1, 100000);
  section.read("goal_similarity", params.goal_similarity, 0.0, 1000.0);
  section.read("goal_confirmations", params.goal_confirmations, 1, 100);
  section.read("unstick_turn_deg", params.unstick_turn_deg, 0.0, 180.0);
  section.read("aim_at_next_place", params.aim_at_next_place);
}

NavigationResult navigate(NavigationWorld& world, const std::vector<PlaceNode>& places,
                          const RoutePlan& initial_plan, const Localiser& localise,
                          const NavigatorParams& params) {
  NavigationResult result;
  RoutePlan plan = initial_plan;
  int expected = -1;  // the place the plan said we would reach next
  int goal_matches = 0;
  // Escaping an obstacle when replanning finds no other route: drive a few steps at an angle
  // from the planned direction, turning the other way each time the robot is blocked again,
  // then follow the plan again.
  int escape_steps_left = 0;
  // Aiming at the next place from the position estimate is left off for a few steps after a
  // block: the estimate that led into the obstacle would lead into it again.
  int steps_since_block = kEscapeSteps + 1;
  int escape_side = 1;
  for (int index = 0; index < params.max_steps; ++index) {
    NavigationStep step;
    step.index = index;
    step.truth = world.truth();
    step.match = localise(world.view(index));
    const int place = step.match.place;
    if (place < 0) {  // nothing recognised (an empty candidate set): go on straight ahead
      result.path_length_m += world.move(0.0, params.step_m);
      result.steps.push_back(step);
      continue;
    }
    step.heading_estimate_rad =
        wrap_angle(places[place].heading_rad + step.match.heading_in_place_rad);
    // A jump: neither where we were, nor where we were heading, nor next to either.
    if (expected >= 0) {
      const Eigen::Vector2d here = places[place].position_m;
      const double near_m = 2.0 * params.step_m + 1e-9;
      step.jump = (here - places[expected].position_m).norm() > near_m &&
                  (result.steps.empty() ||
                   (here - places[result.steps.back().match.place].position_m).norm() > near_m);
      result.jumps += step.jump ? 1 : 0;
    }

    if (place == plan.goal && step.match.similarity >= params.goal_similarity) {
      if (++goal_matches >= params.goal_confirmations) {
        result.steps.push_back(step);
        result.reached = true;
        return result;
      }
    } else {
      goal_matches = 0;
    }

    // Turn to the place's assigned direction, measured against the place's own heading: the
    // robot's heading relative to the place is what the image tells, whatever the lattice.
    double direction_in_place = plan.direction_in_place_rad[place];
    if (place == plan.goal || !plan.reaches_goal(place)) {
      direction_in_place = step.match.heading_in_place_rad;
    } else if (params.aim_at_next_place && step.match.position &&
               steps_since_block > kEscapeSteps) {
      const Eigen::Vector2d to = places[plan.next[place]].position_m - *step.match.position;
      if (to.norm() > 1e-9) {
        direction_in_place =
            signed_difference(std::atan2(to.y(), to.x()), places[place].heading_rad);
      }
    }
    const bool escaping = escape_steps_left > 0;
    if (escaping) {
      direction_in_place += escape_side * deg_to_rad(params.unstick_turn_deg);
      --escape_steps_left;
    }
    step.turn_rad = signed_difference(direction_in_place, step.match.heading_in_place_rad);
    const double driven = world.move(step.turn_rad, params.step_m);
    ++steps_since_block;
    if (driven < 0.5 * params.step_m) {
      steps_since_block = 0;
      if (escaping || !replan_without_link(places, place, plan)) {
        escape_side = -escape_side;
        escape_steps_left = kEscapeSteps;
      } else {
        ++result.replans;
      }
    }
    result.path_length_m += driven;
    expected = plan.next[place] >= 0 ? plan.next[place] : place;
    result.steps.push_back(step);
  }
  return result;
}

}  // namespace omninav::navigation
