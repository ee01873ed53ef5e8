#include "omninav/navigation/memory_places.hpp"

#include <algorithm>
#include <boost/pending/disjoint_sets.hpp>
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
#include "omninav/lattice/similar_places.hpp"
#include "omninav/signature/motion.hpp"

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
  const std::optional<double> link = median_link_dissimilarity(memory);
  if (!link) {
    log_warning(
        "the map has no links between places: images are not checked against a "
        "dissimilarity limit (navigation.yaml route.match_dissimilarity_ratio)");
    return std::numeric_limits<double>::infinity();
  }
  return params.match_dissimilarity_ratio * *link;
}

std::vector<double> link_dissimilarities(const memory::VisualMemory& memory) {
  const double typical =
      median_link_dissimilarity(memory).value_or(std::numeric_limits<double>::infinity());
  std::vector<std::vector<double>> per_place(memory.place_count());
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
    const double d =
        edge.edge->dissimilarity / static_cast<double>(memory.place(edge.from).signature.size());
    // A grid database's order jumps from the end of a row to the start of the next: such a
    // link joins places far apart, and looks it.
    if (d > kFarLinkRatio * typical) continue;
    per_place[edge.from].push_back(d);
    per_place[edge.to].push_back(d);
  }
  std::vector<double> links;
  for (std::vector<double>& own : per_place) {
    links.push_back(own.empty() ? typical : median(std::move(own)));
  }
  return links;
}

double recognition_limit(const memory::VisualMemory& memory, const NavigatorParams& params) {
  const std::optional<double> link = median_link_dissimilarity(memory);
  return link ? params.recognition_link_ratio * *link : std::numeric_limits<double>::infinity();
}

bool is_recognised(const memory::PlaceMatch& match, double limit,
                   const std::vector<double>& place_limits) {
  return match.dissimilarity_per_value <=
         (place_limits.empty() ? limit : place_limits[match.place]);
}

std::vector<double> place_recognition_limits(const memory::VisualMemory& memory,
                                             const NavigatorParams& params) {
  if (params.recognition_place_link_ratio <= 0.0) return {};
  std::vector<double> limits = link_dissimilarities(memory);
  for (double& limit : limits) limit *= params.recognition_place_link_ratio;
  return limits;
}

HomingScale homing_scale(const memory::VisualMemory& memory, const std::vector<PlaceNode>& places) {
  HomingScale scale{memory.parameters().signature, memory.parameters().weights, 0.0};
  const std::optional<double> link = median_link_dissimilarity(memory);
  if (!link || *link <= 0.0) {
    log_warning(
        "the map has no links between distinct places: the navigator stops on recognising the "
        "goal's place, without homing on the goal image");
    return scale;
  }
  scale.metres_per_dissimilarity = lattice_spacing(places) / *link;
  return scale;
}

namespace {

// A link of motion_links before it is kept or dropped.
struct MotionCandidate {
  MeasuredLink link;
  double dissimilarity = 0.0;     // Eq. 2/6 between its places
  double residual = 0.0;          // the worse of the two fits' (MotionEstimate::residual)
  double parallax_rad = 0.0;      // the two fits' mean (MotionEstimate::parallax_rad)
  double disagreement_rad = 0.0;  // between the fit from a and the one from b, reversed
  bool step = false;              // consecutive places of a stream
};

// The direction from a to b relative to a's heading, fitted from a's view and from b's
// reversed, with the turn held at the headings' difference; none when either fit fails.
std::optional<MotionCandidate> fit_link(const memory::VisualMemory& memory,
                                        const std::vector<PlaceNode>& places, int a, int b) {
  const double turn = signed_difference(places[b].heading_rad, places[a].heading_rad);
  const signature::MotionEstimate there =
      signature::estimate_motion(memory.place(a).signature, memory.place(b).signature, -1, turn);
  const signature::MotionEstimate back =
      signature::estimate_motion(memory.place(b).signature, memory.place(a).signature, -1, -turn);
  if (!there.valid || !back.valid) return std::nullopt;
  // b's view of a, turned round and into a's frame.
  const double back_at_a = wrap_angle(back.bearing_rad + kPi + turn);
  const double disagreement = signed_difference(back_at_a, there.bearing_rad);
  const double at_a = wrap_angle(there.bearing_rad + 0.5 * disagreement);
  MotionCandidate candidate;
  candidate.link.places = {a, b};
  candidate.link.direction_at_first_rad = at_a;
  candidate.link.direction_at_second_rad = wrap_angle(at_a + kPi - turn);
  candidate.residual = std::max(there.residual, back.residual);
  candidate.parallax_rad = 0.5 * (there.parallax_rad + back.parallax_rad);
  candidate.disagreement_rad = std::abs(disagreement);
  return candidate;
}

}  // namespace

std::vector<MeasuredLink> motion_links(const memory::VisualMemory& memory,
                                       const std::vector<PlaceNode>& places,
                                       const RouteParams& params) {
  const int count = static_cast<int>(places.size());
  const lattice::PlaceDissimilarities dissimilarity(memory);
  const std::vector<std::vector<lattice::SimilarPlace>> ranking =
      dissimilarity.most_similar(params.motion_neighbours);
  // Each place's dissimilarity to its most similar place: one step there (the calibration's s_a).
  std::vector<double> local_step(count, 0.0);
  for (int a = 0; a < count; ++a) {
    if (!ranking[a].empty()) local_step[a] = ranking[a].front().dissimilarity;
  }
  const double spacing_m = map_spacing(memory, places);

  std::set<Edge> tried;
  std::vector<MotionCandidate> candidates;
  const auto offer = [&](int a, int b, bool step) {
    if (a == b || !tried.insert({std::min(a, b), std::max(a, b)}).second) return;
    std::optional<MotionCandidate> candidate = fit_link(memory, places, a, b);
    if (!candidate) return;
    candidate->dissimilarity = dissimilarity(a, b);
    const double scale = std::sqrt(local_step[a] * local_step[b]);
    candidate->link.length_m =
        scale > 0.0 ? spacing_m * candidate->dissimilarity / scale : spacing_m;
    candidate->step = step;
    candidates.push_back(*candidate);
  };
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
    if (edge.edge->kind == memory::EdgeKind::kSequence) {
      offer(static_cast<int>(edge.from), static_cast<int>(edge.to), true);
    }
  }
  for (int a = 0; a < count; ++a) {
    for (const lattice::SimilarPlace& similar : ranking[a]) offer(a, similar.place, false);
  }
  if (candidates.empty()) return {};

  std::vector<double> residuals, parallaxes;
  for (const MotionCandidate& candidate : candidates) {
    residuals.push_back(candidate.residual);
    parallaxes.push_back(candidate.parallax_rad);
  }
  const double residual_limit = params.motion_residual_ratio * median(std::move(residuals));
  const double parallax_limit = params.motion_parallax_ratio * median(std::move(parallaxes));
  const double disagreement_limit = deg_to_rad(params.motion_disagreement_deg);
  const auto trusted = [&](const MotionCandidate& candidate) {
    return candidate.residual <= residual_limit &&
           (params.motion_parallax_ratio <= 0.0 || candidate.parallax_rad <= parallax_limit) &&
           candidate.disagreement_rad <= disagreement_limit;
  };
  std::vector<int> rank(count, 0), parent(count, 0);
  boost::disjoint_sets<int*, int*> pieces(rank.data(), parent.data());
  for (int place = 0; place < count; ++place) pieces.make_set(place);
  std::vector<MeasuredLink> links;
  std::vector<const MotionCandidate*> dropped;
  for (const MotionCandidate& candidate : candidates) {
    if (candidate.step || trusted(candidate)) {
      links.push_back(candidate.link);
      pieces.union_set(candidate.link.places.first, candidate.link.places.second);
    } else {
      dropped.push_back(&candidate);
    }
  }
  // Joins: the most similar dropped pairs first, those that join places left apart.
  std::sort(dropped.begin(), dropped.end(), [](const MotionCandidate* x, const MotionCandidate* y) {
    return std::tie(x->dissimilarity, x->link.places) < std::tie(y->dissimilarity, y->link.places);
  });
  for (const MotionCandidate* candidate : dropped) {
    const auto [a, b] = candidate->link.places;
    if (pieces.find_set(a) == pieces.find_set(b)) continue;
    links.push_back(candidate->link);
    pieces.union_set(a, b);
  }
  return links;
}

double map_spacing(const memory::VisualMemory& memory, const std::vector<PlaceNode>& places) {
  if (const std::optional<double> grid = memory.grid_spacing_m()) return *grid;
  if (const std::optional<double> every = memory.exploration_spacing_m()) return *every;
  return lattice_spacing(places);
}

bool plans_over_motions(const memory::VisualMemory& memory, const RouteParams& params) {
  switch (params.links) {
    case RouteParams::Links::kLattice:
      return false;
    case RouteParams::Links::kMotions:
      return true;
    case RouteParams::Links::kAuto:
      return memory.lattice_quality() && !memory.lattice_quality()->trustworthy;
  }
  return false;
}

RoutePlan plan_route(const GoalNavigationSetup& setup, int goal) {
  if (!setup.links.empty()) return plan_to_goal(setup.places, setup.links, goal);
  return plan_over_lattice(setup.places, setup.route, goal);
}

RoutePlan plan_over_other_links(const GoalNavigationSetup& setup, int goal) {
  if (setup.navigator.stall_spacings <= 0.0 || !setup.navigator.stall_other_links) return {};
  if (!setup.links.empty()) return plan_over_lattice(setup.places, setup.route, goal);
  if (!setup.other_links.empty()) return plan_to_goal(setup.places, setup.other_links, goal);
  return {};
}

RoutePlan plan_route(const memory::VisualMemory& memory, const std::vector<PlaceNode>& places,
                     const RouteParams& params, int goal) {
  if (plans_over_motions(memory, params)) {
    return plan_to_goal(places, motion_links(memory, places, params), goal);
  }
  return plan_over_lattice(places, params, goal);
}

GoalNavigationSetup goal_navigation_setup(const memory::VisualMemory& memory,
                                          PanoramaLocaliser localise, const RouteParams& route,
                                          const NavigatorParams& navigator) {
  GoalNavigationSetup setup;
  setup.places = places_from_memory(memory);
  setup.localise = std::move(localise);
  setup.match_limit = match_limit(memory, route);
  setup.homing = homing_scale(memory, setup.places);
  setup.route = route;
  if (plans_over_motions(memory, route)) {
    setup.links = motion_links(memory, setup.places, route);
    // Homing's scale from the map's own spacing: a lattice not trusted may be shrunk or folded.
    if (setup.homing.metres_per_dissimilarity > 0.0) {
      setup.homing.metres_per_dissimilarity *=
          map_spacing(memory, setup.places) / lattice_spacing(setup.places);
    }
    log_info("routes run over " + std::to_string(setup.links.size()) +
             " motions measured between places (navigation.yaml route.links: " +
             to_string(route.links) + ")");
  }
  setup.navigator = navigator;
  // A stalled robot switches to the motions when its plan runs over the lattice.
  if (setup.links.empty() && navigator.stall_spacings > 0.0 && navigator.stall_other_links) {
    setup.other_links = motion_links(memory, setup.places, route);
  }
  // Homing's and the stall's distances from the map's spacing: the metres a spacing of this map
  // stands for.
  const double spacing_m = map_spacing(memory, setup.places);
  if (spacing_m > 0.0) setup.navigator.stall_m = navigator.stall_spacings * spacing_m;
  if (navigator.homing_step_spacings > 0.0 && spacing_m > 0.0) {
    setup.navigator.homing_step_m = navigator.homing_step_spacings * spacing_m;
  }
  if (navigator.homing_stop_spacings > 0.0 && spacing_m > 0.0) {
    setup.navigator.homing_stop_m = navigator.homing_stop_spacings * spacing_m;
  }
  setup.recognition_limit = recognition_limit(memory, navigator);
  setup.place_recognition_limits = place_recognition_limits(memory, navigator);
  if (!setup.place_recognition_limits.empty()) {
    log_info("a view is recognised within " + fixed(median(setup.place_recognition_limits), 2) +
             " grey levels per value of its best place, the median over the places "
             "(navigation.yaml navigator.recognition_place_link_ratio times the median "
             "dissimilarity of the place's links)");
  }
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
