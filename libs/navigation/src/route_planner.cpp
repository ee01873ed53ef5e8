#include "omninav/navigation/route_planner.hpp"

#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <cmath>
#include <limits>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/param_check.hpp"
#include "omninav/memory/localisation.hpp"

namespace omninav::navigation {
namespace {

using Graph =
    boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                          boost::property<boost::edge_weight_t, double>>;

void require_place(int place, std::size_t count, const char* what) {
  if (place < 0 || static_cast<std::size_t>(place) >= count) {
    throw UsageError(std::string("route: ") + what + " " + std::to_string(place) +
                     " is not one of the " + std::to_string(count) + " places");
  }
}

}  // namespace

void RouteParams::check() const {
  check_range("route.match_dissimilarity_ratio", match_dissimilarity_ratio, 0.1, 100.0);
  check_range("route.goal_shortlist_ratio", goal_shortlist_ratio, 0.0, 10.0);
}

void load_route_params(const ConfigReader& section, RouteParams& params) {
  section.read("match_dissimilarity_ratio", params.match_dissimilarity_ratio);
  section.read("goal_shortlist_ratio", params.goal_shortlist_ratio);
  check_loaded(section.source_name(), [&] { params.check(); });
}

double lattice_spacing(const std::vector<PlaceNode>& places) {
  std::vector<Eigen::Vector2d> points;
  for (const PlaceNode& place : places) points.push_back(place.position_m);
  return memory::typical_spacing(points);
}

bool RoutePlan::reaches_goal(int place) const {
  return std::isfinite(cost_m.at(place));
}

std::vector<int> RoutePlan::route_from(int start) const {
  if (!reaches_goal(start)) return {};
  std::vector<int> route{start};
  while (route.back() != goal) route.push_back(next[route.back()]);
  return route;
}

namespace {

// Dijkstra from the goal over `edges` weighted by `lengths`: in an undirected graph, each
// place's predecessor on its shortest path from the goal is its next step towards the goal
// (§3.5's search tree). `direction_in_place(place, next, edge)` gives the direction from the
// place to its next one, relative to the place's heading.
template <typename Direction>
RoutePlan search_tree(const std::vector<PlaceNode>& places, const std::vector<PlacePair>& edges,
                      const std::vector<double>& lengths, int goal, Direction direction_in_place) {
  require_place(goal, places.size(), "the goal");
  Graph graph(places.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto& [a, b] = edges[i];
    require_place(a, places.size(), "an edge's place");
    require_place(b, places.size(), "an edge's place");
    boost::add_edge(a, b, lengths[i], graph);
  }
  std::vector<Graph::vertex_descriptor> predecessor(places.size());
  std::vector<double> distance(places.size());
  boost::dijkstra_shortest_paths(
      graph, static_cast<Graph::vertex_descriptor>(goal),
      boost::predecessor_map(predecessor.data()).distance_map(distance.data()));
  // The edge between each place and its predecessor (the shortest of them when several).
  std::vector<std::size_t> via(places.size(), edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    for (const auto& [place, other] : {edges[i], PlacePair(edges[i].second, edges[i].first)}) {
      if (static_cast<int>(predecessor[place]) != other) continue;
      if (via[place] == edges.size() || lengths[i] < lengths[via[place]]) via[place] = i;
    }
  }

  RoutePlan plan;
  plan.goal = goal;
  plan.next.assign(places.size(), -1);
  plan.cost_m.assign(places.size(), std::numeric_limits<double>::infinity());
  plan.direction_rad.assign(places.size(), 0.0);
  plan.direction_in_place_rad.assign(places.size(), 0.0);
  for (std::size_t place = 0; place < places.size(); ++place) {
    if (distance[place] == std::numeric_limits<double>::max()) continue;  // unreachable
    plan.cost_m[place] = distance[place];
    if (static_cast<int>(place) == goal) continue;
    const int next = static_cast<int>(predecessor[place]);
    plan.next[place] = next;
    plan.direction_in_place_rad[place] =
        wrap_angle(direction_in_place(static_cast<int>(place), next, via[place]));
    plan.direction_rad[place] =
        wrap_angle(places[place].heading_rad + plan.direction_in_place_rad[place]);
  }
  return plan;
}

}  // namespace

RoutePlan plan_to_goal(const std::vector<PlaceNode>& places, const std::vector<MeasuredLink>& links,
                       int goal) {
  std::vector<PlacePair> edges;
  std::vector<double> lengths;
  for (const MeasuredLink& link : links) {
    edges.push_back(link.places);
    lengths.push_back(link.length_m);
  }
  RoutePlan plan = search_tree(places, edges, lengths, goal, [&](int place, int, std::size_t edge) {
    const MeasuredLink& link = links[edge];
    return place == link.places.first ? link.direction_at_first_rad : link.direction_at_second_rad;
  });
  plan.links = links;
  return plan;
}

}  // namespace omninav::navigation
