#pragma once
// Route planning over the organised visual memory (001_5bb151a4e28490b4.txt §3.5): from the
// goal, a search tree over the memory graph (Boost.Graph's Dijkstra), which gives every place
// the neighbour to head for next and the direction to it. The direction is given relative to
// the place's own stored heading, so that a robot that recognises the place can follow it
// whatever its own heading (it measures its heading against the place's image by the phase or
// the compass).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace omninav {
class ConfigReader;
}

namespace omninav::navigation {

struct RouteParams {
  // Places closer than this many lattice spacings are neighbours in the memory graph (§3.5
  // plans over the lattice's neighbours; 1.6 takes the 8-neighbourhood of a square grid).
  double neighbour_spacings = 1.6;
  // An image matches a place only when their mean |Δ magnitude| per compared value (the
  // finest level's Eq. 2/6 over lines × components) is at most this many times the median of
  // the map's links (consecutive places of the exploration): an image may look a little less
  // like its best place than neighbouring places look like each other, not much less. Eq. 3's
  // similarity cannot tell: it rescales so that the best place always scores 1000.
  // Chosen across the zoo leaving one family out (config/navigation.yaml, docs/navigation.md):
  // views between the places of a grid map lie below it in every family (>= 99%), views of
  // other worlds and noise above it in the field, in part elsewhere. tests/navigation
  // (MatchThreshold, ZooMatch) check it on rendered grids.
  double match_dissimilarity_ratio = 1.5;
  // What the plan runs over (docs/navigation.md, "Links from the phases"):
  //   kLattice: §3.5's lattice neighbours, each place's direction read off the lattice;
  //   kMotions: the motions measured from the phases (§3.4) between each place and its
  //     motion_neighbours most similar places, those whose fits pass the look-alike checks
  //     (memory_places.hpp, motion_links), each link's direction the measured one: no lattice
  //     position enters the plan;
  //   kAuto: kMotions when the map's stored lattice quality says the lattice is not
  //     trustworthy (lattice/organise.hpp), else kLattice.
  enum class Links { kLattice, kMotions, kAuto };
  Links links = Links::kAuto;
  int motion_neighbours = 4;
  double motion_residual_ratio = 1.5;  // navigation.yaml says how it was chosen
  double motion_parallax_ratio = 0.0;  // 0: the parallax is not checked
  double motion_disagreement_deg = 20.0;
};

// "lattice", "motions", "auto".
std::string to_string(RouteParams::Links links);
// The inverse of to_string; throws UsageError for any other name.
RouteParams::Links route_links_from_string(std::string_view name);

// Reads the `route:` section of navigation.yaml.
void load_route_params(const ConfigReader& section, RouteParams& params);

// A place of the memory as the planner sees it: where the lattice put it, and its stored
// heading in the lattice frame.
struct PlaceNode {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double heading_rad = 0.0;
};

using Edge = std::pair<int, int>;

// The median distance from each place to its nearest neighbour on the lattice.
double lattice_spacing(const std::vector<PlaceNode>& places);

// Links every pair of places closer than `radius_m` on the lattice (the lattice neighbours).
std::vector<Edge> lattice_neighbours(const std::vector<PlaceNode>& places, double radius_m);

// A link of the memory graph whose direction was measured from the phases at both ends (§3.4's
// motion estimate) instead of read off the lattice.
struct MeasuredLink {
  Edge places;                           // (a, b)
  double length_m = 0.0;                 // what the link adds to a route
  double direction_at_first_rad = 0.0;   // from a towards b, relative to a's stored heading
  double direction_at_second_rad = 0.0;  // from b towards a, relative to b's stored heading
};

struct RoutePlan {
  int goal = -1;
  std::vector<Edge> edges;                     // the memory graph it was planned over
  std::vector<MeasuredLink> measured;          // the same with their measured directions, when
                                               // planned over them; empty: the lattice's
  std::vector<int> next;                       // the neighbour to go to next; -1 for the goal and
                                               // for places that cannot reach it
  std::vector<double> cost_m;                  // length of the route to the goal (∞ if none)
  std::vector<double> direction_rad;           // towards `next`, in the lattice frame
  std::vector<double> direction_in_place_rad;  // the same, relative to the place's heading

  bool reaches_goal(int place) const;
  // The places from `start` to the goal, both included; empty when there is no route.
  std::vector<int> route_from(int start) const;
};

// Plans from every place to `goal` over `edges`, weighted by lattice distance. Throws UsageError
// for a goal or an edge that names no place.
RoutePlan plan_to_goal(const std::vector<PlaceNode>& places, const std::vector<Edge>& edges,
                       int goal);

// plan_to_goal over measured links: each link weighted by its length, each place's direction
// the measured one towards its next place (direction_rad: that, plus the place's heading). The
// lattice positions are not read. Throws UsageError as plan_to_goal.
RoutePlan plan_to_goal(const std::vector<PlaceNode>& places, const std::vector<MeasuredLink>& links,
                       int goal);

// The plan without the link between `a` and `b`, from the same goal, over the same kind of links.
RoutePlan plan_without_link(const std::vector<PlaceNode>& places, const RoutePlan& plan, int a,
                            int b);

// plan_to_goal over the lattice neighbours within params.neighbour_spacings lattice spacings.
RoutePlan plan_over_lattice(const std::vector<PlaceNode>& places, const RouteParams& params,
                            int goal);

// String pulling on the lattice (beyond §3.5, whose robot heads for the next place): the
// farthest of the next `links` places of the route from `place` that a straight line from
// `place` reaches without leaving the route, by the lattice alone. The line must pass within
// `tolerance_m` of every place of the route it skips (a route bends round furniture, which
// leaves a hole in the lattice: a line that cuts the bend would cross it), and farther than
// `tolerance_m` from the middle of every link in `blocked` (where the robot met furniture the
// lattice does not show). The next place when no farther one qualifies, `place` itself at the
// goal or without a route.
int look_ahead_place(const std::vector<PlaceNode>& places, const RoutePlan& plan, int place,
                     int links, double tolerance_m, const std::vector<Edge>& blocked);

}  // namespace omninav::navigation
