// omninav route: plan over the organised visual memory from the place of the current image to
// the place of a goal image (Menegatti et al. 2004, §3.5), print the route and draw it.
#include <iostream>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/json.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/io/image_file.hpp"
#include "omninav/measures/png.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "omninav/report/navigation_figures.hpp"
#include "omninav/report/route_output.hpp"

namespace omninav::cli {
namespace {

struct RouteOptions {
  std::filesystem::path map;
  std::filesystem::path from;
  std::filesystem::path to;
  OutputFormat format = OutputFormat::kText;
  std::filesystem::path plot;  // empty: <map>.route.png
};

void run_route(const GlobalOptions& global, const RouteOptions& options) {
  std::filesystem::path plot = options.plot;
  if (plot.empty()) plot = std::filesystem::path(options.map).replace_extension(".route.png");
  check_output_path(plot, {options.map, options.from, options.to});  // before the work
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
      navigation::plan_route(memory, places, navigation.links, static_cast<int>(to.place));
  if (!plan.reaches_goal(from.place)) {
    throw InputError(options.map.string() + ": no route from place " + std::to_string(from.place) +
                     " to place " + std::to_string(to.place) +
                     " over the map's confirmed links (travelled, grid neighbours, revisits)");
  }
  report::Route route = report::make_route(memory, places, plan, from, to);
  route.map = options.map.string();
  route.from_image = options.from.string();
  route.to_image = options.to.string();
  if (options.format == OutputFormat::kCsv) {
    report::write_route_csv(std::cout, route);
  } else if (options.format == OutputFormat::kJson) {
    std::cout << json_text(report::route_json(route)) << "\n";
  } else {
    report::write_route_text(std::cout, route);
  }

  std::optional<std::vector<Eigen::Vector2d>> truth;
  if (memory.all_have_truth()) {
    truth.emplace();
    for (std::size_t i = 0; i < memory.place_count(); ++i)
      truth->emplace_back(memory.place(i).truth->x_m, memory.place(i).truth->y_m);
  }
  measures::save_png(report::route_figure(places, plan, static_cast<int>(from.place), truth), plot);
  log_info("route picture: " + plot.string());
}

}  // namespace

void add_route_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<RouteOptions>();
  CLI::App* command = app.add_subcommand(
      "route",
      "Plan the way from the current image to a goal image over an organised map "
      "(Menegatti et al. 2004, §3.5): localise both, grow the search tree from the goal's "
      "place over the map's confirmed links (Boost.Graph's Dijkstra), give every place its "
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
