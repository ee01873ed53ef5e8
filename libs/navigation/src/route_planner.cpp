#include "omninav/navigation/route_planner.hpp"

#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <cmath>
#include <limits>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
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

// The distance from `point` to the segment from `a` to `b`.
double distance_to_segment(const Eigen::Vector2d& point, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((point - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - point).norm();
}

}  // namespace

void load_route_params(const ConfigReader& section, RouteParams& params) {
  section.read("neighbour_spacings", params.neighbour_spacings, 1.0, 10.0);
  section.read("match_dissimilarity_ratio", params.match_dissimilarity_ratio, 0.1, 100.0);
  std::string links = to_string(params.links);
  section.read("links", links, {"lattice", "motions", "auto"});
  params.links = route_links_from_string(links);
  section.read("motion_neighbours", params.motion_neighbours, 1, 100);
  section.read("motion_residual_ratio", params.motion_residual_ratio, 0.1, 100.0);
  section.read("motion_parallax_ratio", params.motion_parallax_ratio, 0.0, 100.0);
  section.read("motion_disagreement_deg", params.motion_disagreement_deg, 0.0, 180.0);
}

double lattice_spacing(const std::vector<PlaceNode>& places) {
  std::vector<Eigen::Vector2d> points;
  for (const PlaceNode& place : places) points.push_back(place.position_m);
  return memory::typical_spacing(points);
}

std::vector<Edge> lattice_neighbours(const std::vector<PlaceNode>& places, double radius_m) {
  std::vector<Edge> edges;
  for (std::size_t a = 0; a < places.size(); ++a) {
    for (std::size_t b = a + 1; b < places.size(); ++b) {
      if ((places[a].position_m - places[b].position_m).norm() <= radius_m) {
        edges.emplace_back(static_cast<int>(a), static_cast<int>(b));
      }
    }
  }
  return edges;
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
RoutePlan search_tree(const std::vector<PlaceNode>& places, const std::vector<Edge>& edges,
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
    for (const auto& [place, other] : {edges[i], Edge(edges[i].second, edges[i].first)}) {
      if (static_cast<int>(predecessor[place]) != other) continue;
      if (via[place] == edges.size() || lengths[i] < lengths[via[place]]) via[place] = i;
    }
  }

  RoutePlan plan;
  plan.goal = goal;
  plan.edges = edges;
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

std::string to_string(RouteParams::Links links) {
  switch (links) {
    case RouteParams::Links::kLattice:
      return "lattice";
    case RouteParams::Links::kMotions:
      return "motions";
    case RouteParams::Links::kAuto:
      return "auto";
  }
  return "?";
}

RouteParams::Links route_links_from_string(std::string_view name) {
  if (name == "lattice") return RouteParams::Links::kLattice;
  if (name == "motions") return RouteParams::Links::kMotions;
  if (name == "auto") return RouteParams::Links::kAuto;
  throw UsageError("unknown route links '" + std::string(name) +
                   "': expected lattice, motions or auto");
}

RoutePlan plan_to_goal(const std::vector<PlaceNode>& places, const std::vector<Edge>& edges,
                       int goal) {
  std::vector<double> lengths;
  for (const auto& [a, b] : edges) {
    require_place(a, places.size(), "an edge's place");
    require_place(b, places.size(), "an edge's place");
    lengths.push_back((places[a].position_m - places[b].position_m).norm());
  }
  return search_tree(places, edges, lengths, goal, [&](int place, int next, std::size_t) {
    const Eigen::Vector2d step = places[next].position_m - places[place].position_m;
    return signed_difference(std::atan2(step.y(), step.x()), places[place].heading_rad);
  });
}

RoutePlan plan_to_goal(const std::vector<PlaceNode>& places, const std::vector<MeasuredLink>& links,
                       int goal) {
  std::vector<Edge> edges;
  std::vector<double> lengths;
  for (const MeasuredLink& link : links) {
    edges.push_back(link.places);
    lengths.push_back(link.length_m);
  }
  RoutePlan plan = search_tree(places, edges, lengths, goal, [&](int place, int, std::size_t edge) {
    const MeasuredLink& link = links[edge];
    return place == link.places.first ? link.direction_at_first_rad : link.direction_at_second_rad;
  });
  plan.measured = links;
  return plan;
}

RoutePlan plan_without_link(const std::vector<PlaceNode>& places, const RoutePlan& plan, int a,
                            int b) {
  const auto other = [&](const Edge& edge) { return edge != Edge(a, b) && edge != Edge(b, a); };
  if (!plan.measured.empty()) {
    std::vector<MeasuredLink> links;
    for (const MeasuredLink& link : plan.measured) {
      if (other(link.places)) links.push_back(link);
    }
    return plan_to_goal(places, links, plan.goal);
  }
  std::vector<Edge> edges;
  for (const Edge& edge : plan.edges) {
    if (other(edge)) edges.push_back(edge);
  }
  return plan_to_goal(places, edges, plan.goal);
}

int look_ahead_place(const std::vector<PlaceNode>& places, const RoutePlan& plan, int place,
                     int links, double tolerance_m, const std::vector<Edge>& blocked) {
  const std::vector<int> route = plan.route_from(place);
  if (route.size() < 2) return place;
  const Eigen::Vector2d from = places[place].position_m;
  const auto clear = [&](const Eigen::Vector2d& to, std::size_t skipped) {
    for (std::size_t i = 1; i <= skipped; ++i) {
      if (distance_to_segment(places[route[i]].position_m, from, to) > tolerance_m) return false;
    }
    for (const auto& [a, b] : blocked) {
      const Eigen::Vector2d middle = 0.5 * (places[a].position_m + places[b].position_m);
      if (distance_to_segment(middle, from, to) <= tolerance_m) return false;
    }
    return true;
  };
  std::size_t ahead = 1;
  const std::size_t last = std::min(route.size() - 1, static_cast<std::size_t>(std::max(links, 1)));
  while (ahead < last && clear(places[route[ahead + 1]].position_m, ahead)) ++ahead;
  return route[ahead];
}

RoutePlan plan_over_lattice(const std::vector<PlaceNode>& places, const RouteParams& params,
                            int goal) {
  return plan_to_goal(
      places, lattice_neighbours(places, params.neighbour_spacings * lattice_spacing(places)),
      goal);
}

}  // namespace omninav::navigation
