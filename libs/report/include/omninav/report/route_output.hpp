// The printed route of `omninav route` (the companion paper's §3.5, Menegatti et al. 2004): the
// places from the current place to the goal's, as text, CSV or JSON.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "omninav/core/json.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/navigation/route_planner.hpp"

namespace omninav::report {

// One place of the route, as printed.
struct RouteStep {
  int place = 0;
  Eigen::Vector2d lattice_position = Eigen::Vector2d::Zero();
  double cost = 0.0;                    // route length left to the goal, lattice units
  std::optional<double> direction_deg;  // towards the next place, lattice frame; none at the goal
  std::optional<double> direction_in_place_deg;   // the same from the place's stored heading
  std::optional<Eigen::Vector2d> world_position;  // the place's true position (m), if stored
};

// The route from the place of the current image (`from`) to the goal image's place (`to`).
struct Route {
  std::string map, from_image, to_image;  // as the user named them
  memory::PlaceMatch from, to;
  std::vector<RouteStep> steps;    // from `from` to the goal, never empty
  std::optional<double> turn_deg;  // the start: turn from the robot's heading now
};

// The route of `plan` from the place `from` matched, with the places' positions and truths.
Route make_route(const memory::VisualMemory& memory,
                 const std::vector<navigation::PlaceNode>& places,
                 const navigation::RoutePlan& plan, const memory::PlaceMatch& from,
                 const memory::PlaceMatch& to);

// A header line, the turn to take now, and a table of the places.
void write_route_text(std::ostream& out, const Route& route);
// One row per place: step, place, lattice_x, lattice_y, cost, direction_deg,
// direction_in_place_deg, turn_from_robot_deg (first row), truth_x_m, truth_y_m.
void write_route_csv(std::ostream& out, const Route& route);
// Numbers at full precision: JSON is for programs.
Json route_json(const Route& route);

}  // namespace omninav::report
