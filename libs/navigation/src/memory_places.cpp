#include "omninav/navigation/memory_places.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/lattice/organise.hpp"
#include "omninav/signature/dissimilarity.hpp"

namespace omninav::navigation {

std::vector<PlaceNode> places_from_memory(const memory::VisualMemory& memory) {
  if (memory.place_count() == 0) throw InputError("the map has no places");
  if (!memory.all_have_lattice()) {
    throw UsageError("the map has no lattice yet: run 'omninav organise' on it first");
  }
  const std::vector<std::optional<double>> headings = lattice::lattice_headings(memory);
  std::vector<PlaceNode> places;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    if (!headings[i]) {
      throw UsageError("place " + std::to_string(i) +
                       " has no heading, stored or measured along the exploration: the navigator "
                       "cannot tell the robot which way to turn there");
    }
    places.push_back({*memory.place(i).lattice_position, *headings[i]});
  }
  return places;
}

PanoramaLocaliser memory_localiser(const memory::Localiser& localiser,
                                   signature::SignatureExtractor& extractor) {
  return [&localiser, &extractor](const cv::Mat& panorama) {
    const int rows = localiser.memory().parameters().panorama_rows;
    if (panorama.rows != rows) {
      throw InputError("a panorama of " + std::to_string(panorama.rows) + " rows; the map's have " +
                       std::to_string(rows));
    }
    return localiser.localise(extractor.compute(panorama, "the robot's view"));
  };
}

std::optional<std::string> no_match_reason(const memory::Localisation& localisation, double limit) {
  if (localisation.best.empty()) return "matches no place of the map (no candidate)";
  const memory::PlaceMatch& match = localisation.best.front();
  if (!(match.dissimilarity_per_value <= limit)) {
    return "matches no place of the map (the nearest, place " + std::to_string(match.place) +
           ", differs by " + fixed(match.dissimilarity_per_value, 2) +
           " grey levels per compared value, more than " + fixed(limit, 2) +
           ": navigation.yaml route.match_dissimilarity_ratio times the map's typical difference "
           "between neighbouring places)";
  }
  return std::nullopt;
}

namespace {

// A link more than this many times the map's median link joins places more than a spacing or
// two apart (link_dissimilarities).
constexpr double kFarLinkRatio = 2.0;

// The median over the map's links of their dissimilarity per value; none without links.
std::optional<double> median_link_dissimilarity(const memory::VisualMemory& memory) {
  std::vector<double> links;
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
    links.push_back(edge.edge->dissimilarity /
                    static_cast<double>(memory.place(edge.from).signature.size()));
  }
  if (links.empty()) return std::nullopt;
  return median(std::move(links));
}

}  // namespace

double match_limit(const memory::VisualMemory& memory, const RouteParams& params) {
  params.check();
  const std::optional<double> link = median_link_dissimilarity(memory);
  if (!link) {
    log_warning(
        "the map has no links between places: images are not checked against a "
        "dissimilarity limit (navigation.yaml route.match_dissimilarity_ratio)");
    return std::numeric_limits<double>::infinity();
  }
  return params.match_dissimilarity_ratio * *link;
}

double recognition_limit(const memory::VisualMemory& memory) {
  return median_link_dissimilarity(memory).value_or(std::numeric_limits<double>::infinity());
}

HomingScale homing_scale(const memory::VisualMemory& memory, const std::vector<PlaceNode>& places) {
  HomingScale scale{memory.parameters().signature, memory.parameters().weights, 0.0, nullptr};
  const std::optional<double> link = median_link_dissimilarity(memory);
  if (!link || *link <= 0.0) {
    log_warning(
        "the map has no links between distinct places: the navigator stops on recognising the "
        "goal's place, without homing on the goal image");
    return scale;
  }
  scale.metres_per_dissimilarity = map_spacing(memory, places) / *link;
  return scale;
}

double map_spacing(const memory::VisualMemory& memory, const std::vector<PlaceNode>& places) {
  if (const std::optional<double> grid = memory.grid_spacing_m()) return *grid;
  if (const std::optional<double> every = memory.exploration_spacing_m()) return *every;
  return lattice_spacing(places);
}

std::vector<MeasuredLink> map_links(const memory::VisualMemory& memory,
                                    const std::vector<PlaceNode>& places,
                                    const LinkParams& params) {
  std::vector<double> headings;
  std::vector<Eigen::Vector2d> positions;
  for (const PlaceNode& place : places) {
    headings.push_back(place.heading_rad);
    positions.push_back(place.position_m);
  }
  std::vector<MeasuredLink> links =
      lattice::confirmed_links(memory, headings, map_spacing(memory, places), params);
  const std::vector<MeasuredLink> neighbours =
      lattice::lattice_neighbour_links(memory, positions, links, params);
  links.insert(links.end(), neighbours.begin(), neighbours.end());
  return links;
}

RoutePlan plan_route(const memory::VisualMemory& memory, const std::vector<PlaceNode>& places,
                     const LinkParams& links, int goal) {
  return plan_to_goal(places, map_links(memory, places, links), goal);
}

GoalNavigationSetup goal_navigation_setup(const memory::VisualMemory& memory,
                                          PanoramaLocaliser localise, const RouteParams& route,
                                          const NavigatorParams& navigator, const LinkParams& links,
                                          const BeliefParams& belief,
                                          const SteeringParams& steering) {
  navigator.check();
  belief.check();
  GoalNavigationSetup setup;
  setup.places = places_from_memory(memory);
  setup.localise = std::move(localise);
  setup.match_limit = match_limit(memory, route);
  setup.goal_shortlist_ratio = route.goal_shortlist_ratio;
  setup.homing = homing_scale(memory, setup.places);
  setup.navigator = navigator;
  // Homing's distances from the map's spacing: the metres a spacing of this map stands for.
  const double spacing_m = map_spacing(memory, setup.places);
  if (navigator.homing_step_spacings > 0.0 && spacing_m > 0.0) {
    setup.navigator.homing_step_m = navigator.homing_step_spacings * spacing_m;
  }
  if (navigator.homing_stop_spacings > 0.0 && spacing_m > 0.0) {
    setup.navigator.homing_stop_m = navigator.homing_stop_spacings * spacing_m;
  }
  setup.links = map_links(memory, setup.places, links);
  if (setup.links.empty()) {
    log_warning(
        "the map has no confirmed links (a single place, or an unordered input without grid "
        "positions): the robot cannot plan a route and drives on its belief alone");
  }
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    setup.signatures.push_back(memory.place(i).signature);
  }
  setup.weights = memory.parameters().weights;
  const std::optional<double> link = lattice::median_dissimilarity_per_value(memory, setup.links);
  if (link && *link > 0.0) setup.link_dissimilarity = *link;
  // The extractor is shared by the copies of the setup: one navigation at a time.
  auto extractor = std::make_shared<signature::SignatureExtractor>(memory.parameters().signature);
  setup.signature_of = [extractor](const cv::Mat& panorama) {
    return extractor->compute(panorama, "the robot's view");
  };
  setup.belief = belief;
  auto snapshots = std::make_shared<PlaceSnapshots>();
  snapshots->warping = std::make_shared<compass::MinWarping>(steering.warping, steering.panorama);
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    snapshots->thumbnails_png.push_back(memory.place(i).thumbnail_png);
  }
  setup.homing.warping = snapshots->warping;
  setup.snapshots = std::move(snapshots);
  return setup;
}

memory::PlaceMatch match_image(const PanoramaLocaliser& localise, const cv::Mat& image,
                               double limit, const std::string& what) {
  require_panorama(image, what);
  memory::Localisation localisation;
  try {
    localisation = localise(image);
  } catch (const InputError& error) {
    throw InputError(what + ": " + error.what());
  }
  if (const std::optional<std::string> reason = no_match_reason(localisation, limit)) {
    throw InputError(what + ": " + *reason);
  }
  return localisation.best.front();
}

}  // namespace omninav::navigation
