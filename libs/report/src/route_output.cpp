#include "omninav/report/route_output.hpp"

#include <iomanip>

#include "omninav/core/angles.hpp"
#include "omninav/core/format.hpp"

namespace omninav::report {

Route make_route(const memory::VisualMemory& memory,
                 const std::vector<navigation::PlaceNode>& places,
                 const navigation::RoutePlan& plan, const memory::PlaceMatch& from,
                 const memory::PlaceMatch& to) {
  Route route;
  route.from = from;
  route.to = to;
  for (const int place : plan.route_from(static_cast<int>(from.place))) {
    RouteStep step;
    step.place = place;
    step.lattice_position = places[place].position_m;
    step.cost = plan.cost_m[place];
    if (place != plan.goal) {
      step.direction_deg = rad_to_deg(plan.direction_rad[place]);
      step.direction_in_place_deg = rad_to_deg(plan.direction_in_place_rad[place]);
    }
    if (const std::optional<CameraPose>& truth = memory.place(place).truth)
      step.world_position = truth->floor_position();
    route.steps.push_back(step);
  }
  if (static_cast<int>(from.place) != plan.goal) {
    route.turn_deg = rad_to_deg(
        signed_difference(plan.direction_in_place_rad[from.place], from.relative_heading_rad));
  }
  return route;
}

void write_route_text(std::ostream& out, const Route& route) {
  out << "route from " << route.from_image << " (place " << route.from.place << ", dissimilarity "
      << fixed(route.from.dissimilarity_per_value, 2) << " per value) to " << route.to_image
      << " (place " << route.to.place << ", " << fixed(route.to.dissimilarity_per_value, 2)
      << "): " << route.steps.size() << " place" << (route.steps.size() == 1 ? "" : "s") << ", "
      << fixed(route.steps.front().cost, 2) << " lattice units\n";
  if (route.turn_deg) {
    out << "now: turn " << signed_fixed(*route.turn_deg, 1)
        << " deg (counter-clockwise positive) from the robot's heading, then go\n";
  } else {
    out << "now: the current image already matches the goal's place\n";
  }
  out << "  place  lattice x,y      to goal  direction  from place's heading\n";
  for (const RouteStep& step : route.steps) {
    out << "  " << std::setw(5) << step.place << "  " << std::setw(7)
        << fixed(step.lattice_position.x(), 2) << "," << std::setw(7)
        << fixed(step.lattice_position.y(), 2) << "  " << std::setw(7) << fixed(step.cost, 2)
        << "  ";
    if (step.direction_deg) {
      out << std::setw(9) << fixed(*step.direction_deg, 1) << "  " << std::setw(9)
          << fixed(*step.direction_in_place_deg, 1) << " deg";
    } else {
      out << "     goal";
    }
    if (step.world_position) {
      out << "   (truth " << fixed(step.world_position->x(), 2) << ", "
          << fixed(step.world_position->y(), 2) << " m)";
    }
    out << "\n";
  }
}

void write_route_csv(std::ostream& out, const Route& route) {
  out << "step,place,lattice_x,lattice_y,cost,direction_deg,direction_in_place_deg,"
         "turn_from_robot_deg,truth_x_m,truth_y_m\n";
  for (std::size_t i = 0; i < route.steps.size(); ++i) {
    const RouteStep& step = route.steps[i];
    out << i << ',' << step.place << ',' << fixed(step.lattice_position.x(), 4) << ','
        << fixed(step.lattice_position.y(), 4) << ',' << fixed(step.cost, 4) << ','
        << fixed_or_empty(step.direction_deg, 3) << ','
        << fixed_or_empty(step.direction_in_place_deg, 3) << ','
        << (i == 0 ? fixed_or_empty(route.turn_deg, 3) : "") << ','
        << (step.world_position ? fixed(step.world_position->x(), 4) : "") << ','
        << (step.world_position ? fixed(step.world_position->y(), 4) : "") << '\n';
  }
}

Json route_json(const Route& route) {
  const auto match = [](const std::string& image, const memory::PlaceMatch& m) {
    return Json{{"image", image},
                {"place", static_cast<int>(m.place)},
                {"dissimilarity_per_value", m.dissimilarity_per_value},
                {"heading_in_place_deg", rad_to_deg(m.relative_heading_rad)}};
  };
  Json json{{"map", route.map},
            {"from", match(route.from_image, route.from)},
            {"to", match(route.to_image, route.to)},
            {"length", route.steps.front().cost}};
  if (route.turn_deg) json["turn_from_robot_deg"] = *route.turn_deg;
  Json steps = Json::array();
  for (const RouteStep& step : route.steps) {
    Json place{{"place", step.place},
               {"lattice_x", step.lattice_position.x()},
               {"lattice_y", step.lattice_position.y()},
               {"cost", step.cost}};
    if (step.direction_deg) {
      place["direction_deg"] = *step.direction_deg;
      place["direction_in_place_deg"] = *step.direction_in_place_deg;
    }
    if (step.world_position) {
      place["truth_x_m"] = step.world_position->x();
      place["truth_y_m"] = step.world_position->y();
    }
    steps.push_back(std::move(place));
  }
  json["route"] = std::move(steps);
  return json;
}

}  // namespace omninav::report
