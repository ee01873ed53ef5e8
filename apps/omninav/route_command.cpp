// omninav route: plan over the organised visual memory from the place of the current image to
// the place of a goal image (001_5bb151a4e28490b4.txt §3.5), print the route and draw it.
#include <iomanip>
#include <iostream>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/json.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/eval/png.hpp"
#include "omninav/io/image_file.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "omninav/report/navigation_figures.hpp"

namespace omninav::cli {
namespace {

struct RouteOptions {
  std::filesystem::path map;
  std::filesystem::path from;
  std::filesystem::path to;
  OutputFormat format = OutputFormat::kText;
  std::filesystem::path plot;  // empty: <map>.route.png
};

// One place of the route, as printed.
struct RouteStep {
  int place = 0;
  Eigen::Vector2d lattice = Eigen::Vector2d::Zero();
  double cost = 0.0;                    // route length left to the goal, lattice units
  std::optional<double> direction_deg;  // towards the next place, lattice frame; none at the goal
  std::optional<double> direction_in_place_deg;  // the same from the place's stored heading
  std::optional<Eigen::Vector2d> truth_m;        // the place's true position, when the map has it
};

struct Route {
  memory::PlaceMatch from, to;
  std::vector<RouteStep> steps;
  std::optional<double> turn_deg;  // the start: turn from the robot's heading now
};

Route make_route(const memory::VisualMemory& memory,
                 const std::vector<navigation::PlaceNode>& places,
                 const navigation::RoutePlan& plan, const memory::PlaceMatch& from,
                 const memory::PlaceMatch& to) {
  Route route{from, to, {}, std::nullopt};
  for (const int place : plan.route_from(static_cast<int>(from.place))) {
    RouteStep step;
    step.place = place;
    step.lattice = places[place].position_m;
    step.cost = plan.cost_m[place];
    if (place != plan.goal) {
      step.direction_deg = rad_to_deg(plan.direction_rad[place]);
      step.direction_in_place_deg = rad_to_deg(plan.direction_in_place_rad[place]);
    }
    if (const std::optional<CameraPose>& truth = memory.place(place).truth)
      step.truth_m = Eigen::Vector2d(truth->x_m, truth->y_m);
    route.steps.push_back(step);
  }
  if (static_cast<int>(from.place) != plan.goal) {
    route.turn_deg = rad_to_deg(
        signed_difference(plan.direction_in_place_rad[from.place], from.relative_heading_rad));
  }
  return route;
}

void print_text(const Route& route, const RouteOptions& options) {
  std::cout << "route from " << options.from.string() << " (place " << route.from.place
            << ", dissimilarity " << fixed(route.from.dissimilarity_per_value, 2)
            << " per value) to " << options.to.string() << " (place " << route.to.place << ", "
            << fixed(route.to.dissimilarity_per_value, 2) << "): " << route.steps.size() << " place"
            << (route.steps.size() == 1 ? "" : "s") << ", " << fixed(route.steps.front().cost, 2)
            << " lattice units\n";
  if (route.turn_deg) {
    std::cout << "now: turn " << signed_fixed(*route.turn_deg, 1)
              << " deg (counter-clockwise positive) from the robot's heading, then go\n";
  } else {
    std::cout << "now: the current image already matches the goal's place\n";
  }
  std::cout << "  place  lattice x,y      to goal  direction  from place's heading\n";
  for (const RouteStep& step : route.steps) {
    std::cout << "  " << std::setw(5) << step.place << "  " << std::setw(7)
              << fixed(step.lattice.x(), 2) << "," << std::setw(7) << fixed(step.lattice.y(), 2)
              << "  " << std::setw(7) << fixed(step.cost, 2) << "  ";
    if (step.direction_deg) {
      std::cout << std::setw(9) << fixed(*step.direction_deg, 1) << "  " << std::setw(9)
                << fixed(*step.direction_in_place_deg, 1) << " deg";
    } else {
      std::cout << "     goal";
    }
    if (step.truth_m) {
      std::cout << "   (truth " << fixed(step.truth_m->x(), 2) << ", "
                << fixed(step.truth_m->y(), 2) << " m)";
    }
    std::cout << "\n";
  }
}

void print_csv(const Route& route) {
  std::cout << "step,place,lattice_x,lattice_y,cost,direction_deg,direction_in_place_deg,"
               "turn_from_robot_deg,truth_x_m,truth_y_m\n";
  for (std::size_t i = 0; i < route.steps.size(); ++i) {
    const RouteStep& step = route.steps[i];
    std::cout << i << ',' << step.place << ',' << fixed(step.lattice.x(), 4) << ','
              << fixed(step.lattice.y(), 4) << ',' << fixed(step.cost, 4) << ','
              << fixed_or_empty(step.direction_deg, 3) << ','
              << fixed_or_empty(step.direction_in_place_deg, 3) << ','
              << (i == 0 ? fixed_or_empty(route.turn_deg, 3) : "") << ','
              << (step.truth_m ? fixed(step.truth_m->x(), 4) : "") << ','
              << (step.truth_m ? fixed(step.truth_m->y(), 4) : "") << '\n';
  }
}

// Numbers at full precision: JSON is for programs.
void print_json(const Route& route, const RouteOptions& options) {
  const auto match = [](const std::filesystem::path& image, const memory::PlaceMatch& m) {
    return Json{{"image", image.string()},
                {"place", static_cast<int>(m.place)},
                {"dissimilarity_per_value", m.dissimilarity_per_value},
                {"heading_in_place_deg", rad_to_deg(m.relative_heading_rad)}};
  };
  Json json{{"map", options.map.string()},
            {"from", match(options.from, route.from)},
            {"to", match(options.to, route.to)},
            {"length", route.steps.front().cost}};
  if (route.turn_deg) json["turn_from_robot_deg"] = *route.turn_deg;
  Json steps = Json::array();
  for (const RouteStep& step : route.steps) {
    Json place{{"place", step.place},
               {"lattice_x", step.lattice.x()},
               {"lattice_y", step.lattice.y()},
               {"cost", step.cost}};
    if (step.direction_deg) {
      place["direction_deg"] = *step.direction_deg;
      place["direction_in_place_deg"] = *step.direction_in_place_deg;
    }
    if (step.truth_m) {
      place["truth_x_m"] = step.truth_m->x();
      place["truth_y_m"] = step.truth_m->y();
    }
    steps.push_back(std::move(place));
  }
  json["route"] = std::move(steps);
  std::cout << json_text(json) << "\n";
}

void run_route(const GlobalOptions& global, const RouteOptions& options) {
  std::filesystem::path plot = options.plot;
  if (plot.empty()) plot = std::filesystem::path(options.map).replace_extension(".route.png");
  check_output_path(plot);  // before the work
  const memory::MemoryConfig memory_config = load_memory_config(global.config_dir);
  const NavigationConfig navigation = load_navigation_config(global.config_dir);
  const memory::VisualMemory memory = memory::load_map(options.map);
  std::vector<navigation::PlaceNode> places;
  try {
    places = navigation::places_from_memory(memory);
  } catch (const InputError& error) {
    throw InputError(options.map.string() + ": " + error.what());
  } catch (const UsageError& error) {
    throw UsageError(options.map.string() + ": " + error.what());
  }
  const memory::Localiser localiser(memory, memory_config.localisation);
  signature::SignatureExtractor extractor(memory.parameters().signature);
  const navigation::PanoramaLocaliser localise = navigation::memory_localiser(localiser, extractor);
  const double limit = navigation::match_limit(memory, navigation.route);
  const memory::PlaceMatch from =
      navigation::match_image(localise, io::read_image(options.from), limit, options.from.string());
  const memory::PlaceMatch to =
      navigation::match_image(localise, io::read_image(options.to), limit, options.to.string());

  // §3.5: the search tree grows from the goal, so every place gets its direction at once.
  const navigation::RoutePlan plan =
      navigation::plan_over_lattice(places, navigation.route, static_cast<int>(to.place));
  if (!plan.reaches_goal(from.place)) {
    throw InputError(options.map.string() + ": no route from place " + std::to_string(from.place) +
                     " to place " + std::to_string(to.place) +
                     " over the lattice neighbours (within " +
                     fixed(navigation.route.neighbour_spacings, 1) + " spacings)");
  }
  const Route route = make_route(memory, places, plan, from, to);
  if (options.format == OutputFormat::kCsv) {
    print_csv(route);
  } else if (options.format == OutputFormat::kJson) {
    print_json(route, options);
  } else {
    print_text(route, options);
  }

  std::optional<std::vector<Eigen::Vector2d>> truth;
  if (memory.all_have_truth()) {
    truth.emplace();
    for (std::size_t i = 0; i < memory.place_count(); ++i)
      truth->emplace_back(memory.place(i).truth->x_m, memory.place(i).truth->y_m);
  }
  eval::save_png(report::route_figure(places, plan, static_cast<int>(from.place), truth), plot);
  log_info("route picture: " + plot.string());
}

}  // namespace

void add_route_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<RouteOptions>();
  CLI::App* command = app.add_subcommand(
      "route",
      "Plan the way from the current image to a goal image over an organised map "
      "(001_5bb151a4e28490b4.txt §3.5): localise both, grow the search tree from the goal's "
      "place over the lattice neighbours (Boost.Graph's Dijkstra), give every place its "
      "direction towards the goal relative to the place's stored heading, and print the route "
      "from the current place: its places, lattice positions, the direction to take at each, "
      "and the turn from the robot's heading now. Draws the lattice with every place's "
      "direction and the route (and the route over the places' true positions when the map has "
      "ground truth).");
  command->add_option("map", options->map, "An organised map (.vmem)")->required();
  command->add_option("--from", options->from, "The current image (a panorama)")->required();
  command->add_option("--to", options->to, "The goal image (a panorama)")->required();
  add_format_option(command, options->format);
  command->add_option("--plot", options->plot, "The route picture (default: <map>.route.png)");
  command->callback([&global, options] { run_route(global, *options); });
}

}  // namespace omninav::cli
