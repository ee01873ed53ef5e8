#pragma once
// Route planning over the visual memory (Menegatti et al. 2004, §3.5): from the goal, a search
// tree over the memory graph (Boost.Graph's Dijkstra), which gives every place the neighbour to
// head for next and the direction to it. The graph is the map's confirmed links
// (confirmed_links.hpp), each weighted by its length; the direction is the link's, relative to
// the place's own stored heading, so that a robot that recognises the place can follow it
// whatever its own heading (it measures its heading against the place's image by the phases).

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "omninav/lattice/confirmed_links.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::navigation {

struct RouteParams {
  // An image matches a place only when their mean |Δ magnitude| per compared value (the
  // finest level's Eq. 2/6 over lines × components) is at most this many times the median of
  // the map's links (consecutive places of the exploration): an image may look a little less
  // like its best place than neighbouring places look like each other, not much less. Eq. 3's
  // similarity cannot tell: it rescales so that the best place always scores 1000.
  // Chosen across the zoo leaving one family out (config/navigation.yaml).
  double match_dissimilarity_ratio = 1.5;
  // The goal image's place, coarse to fine (recognise_goal, goal_navigation.hpp): the places
  // whose dissimilarity to the goal image is within this many times the map's median link
  // dissimilarity of the least are compared with it by min-warping, and the best match is the
  // goal's place. A look-alike a few centimetres or a desk row away differs from the goal image
  // by a fraction of a link; the Fourier signature's magnitudes cannot tell them apart, the
  // whole image can. 0: the signature's best place alone. Chosen across the zoo leaving one
  // family out (config/navigation.yaml).
  double goal_shortlist_ratio = 0.2;

  // The range of navigation.yaml's route section. Throws UsageError naming the key
  // (core/param_check.hpp); the loader and match_limit (memory_places.hpp) call it.
  void check() const;
};

// Reads the `route:` section of navigation.yaml.
void load_route_params(const ConfigReader& section, RouteParams& params);

// A place of the memory as the planner sees it: its stored heading in the map's frame, and
// where the lattice put it (for pictures; nothing of the plan reads it).
struct PlaceNode {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double heading_rad = 0.0;
};

using PlacePair = std::pair<int, int>;  // two places' indices (a link's ends)

// The median distance from each place to its nearest neighbour on the lattice.
double lattice_spacing(const std::vector<PlaceNode>& places);

// The memory graph's links (lattice/confirmed_links.hpp), as the plan and the belief use them.
using lattice::LinkKind;
using lattice::LinkParams;
using lattice::MeasuredLink;

struct RoutePlan {
  int goal = -1;
  std::vector<MeasuredLink> links;             // the memory graph it was planned over
  std::vector<int> next;                       // the neighbour to go to next; -1 for the goal and
                                               // for places that cannot reach it
  std::vector<double> cost_m;                  // length of the route to the goal (∞ if none)
  std::vector<double> direction_rad;           // towards `next`, in the map's frame
  std::vector<double> direction_in_place_rad;  // the same, relative to the place's heading

  bool reaches_goal(int place) const;
  // The places from `start` to the goal, both included; empty when there is no route.
  std::vector<int> route_from(int start) const;
};

// Plans from every place to `goal` over `links`: each link weighted by its length, each place's
// direction the link's towards its next place (direction_rad: that, plus the place's heading).
// Throws UsageError for a goal or a link that names no place.
RoutePlan plan_to_goal(const std::vector<PlaceNode>& places, const std::vector<MeasuredLink>& links,
                       int goal);

}  // namespace omninav::navigation
