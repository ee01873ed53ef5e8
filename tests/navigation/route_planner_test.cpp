#include "omninav/navigation/route_planner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::navigation {
namespace {

// A 4×3 grid of places 1 m apart, with a wall: the edges between columns 1 and 2 are cut
// except in the top row, so routes must go round through it.
//   8  9 10 11
//   4  5 |6  7
//   0  1 |2  3
std::vector<PlaceNode> grid_places() {
  std::vector<PlaceNode> places;
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) places.push_back({Eigen::Vector2d(x, y), 0.0});
  }
  return places;
}

std::vector<Edge> grid_edges_with_wall() {
  std::vector<Edge> edges;
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) {
      const int place = 4 * y + x;
      if (x + 1 < 4 && !(x == 1 && y < 2)) edges.emplace_back(place, place + 1);
      if (y + 1 < 3) edges.emplace_back(place, place + 4);
    }
  }
  return edges;
}

TEST(RoutePlanner, ReturnsTheShortestPathRoundTheWall) {
  const RoutePlan plan = plan_to_goal(grid_places(), grid_edges_with_wall(), 3);
  // From 0 the shortest routes to 3 go up to the top row, across and down: 7 steps. From 1
  // there is one shortest route, through 5, 9, 10, 6 and 2 (6 steps).
  EXPECT_DOUBLE_EQ(plan.cost_m[0], 7.0);
  EXPECT_DOUBLE_EQ(plan.cost_m[1], 6.0);
  EXPECT_EQ(plan.route_from(1), (std::vector<int>{1, 5, 9, 10, 6, 2, 3}));
  EXPECT_EQ(plan.route_from(3), (std::vector<int>{3}));
  EXPECT_EQ(plan.next[3], -1);
}

TEST(RoutePlanner, DirectionsAreRelativeToEachPlacesHeading) {
  std::vector<PlaceNode> places = grid_places();
  places[5].heading_rad = deg_to_rad(90.0);  // the image at place 5 was taken facing +y
  const RoutePlan plan = plan_to_goal(places, grid_edges_with_wall(), 3);
  // From 5 the route goes up to 9: +y in the lattice, straight ahead for place 5's image.
  EXPECT_EQ(plan.next[5], 9);
  EXPECT_NEAR(plan.direction_rad[5], deg_to_rad(90.0), 1e-12);
  EXPECT_NEAR(plan.direction_in_place_rad[5], 0.0, 1e-12);
  // From 2 the route goes right to 3 (+x): for a place facing +x that is straight ahead too;
  // from 6 it goes down (−y): 90° to the right.
  EXPECT_NEAR(plan.direction_in_place_rad[6], deg_to_rad(-90.0), 1e-12);
}

TEST(RoutePlanner, UnreachablePlacesHaveNoRoute) {
  std::vector<PlaceNode> places = grid_places();
  places.push_back({Eigen::Vector2d(10.0, 10.0), 0.0});  // an island
  const RoutePlan plan = plan_to_goal(places, grid_edges_with_wall(), 0);
  EXPECT_FALSE(plan.reaches_goal(12));
  EXPECT_TRUE(plan.route_from(12).empty());
  EXPECT_TRUE(plan.reaches_goal(11));
}

TEST(RoutePlanner, LatticeNeighboursWithinARadius) {
  const std::vector<Edge> edges = lattice_neighbours(grid_places(), 1.0);
  EXPECT_EQ(edges.size(), 17u);  // 3 rows × 3 + 4 columns × 2
  EXPECT_EQ(lattice_neighbours(grid_places(), 1.5).size(), 17u + 12u);  // and the diagonals
}

// Whether the segment from `a` to `b` crosses the wall of grid_edges_with_wall(): the cut
// links run between columns 1 and 2 in the two lower rows, so the wall stands at x = 1.5 from
// below the grid up to between rows 1 and 2.
bool crosses_wall(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  if ((a.x() - 1.5) * (b.x() - 1.5) >= 0.0) return false;
  const double y = a.y() + (b.y() - a.y()) * (1.5 - a.x()) / (b.x() - a.x());
  return y < 1.5;
}

TEST(RoutePlanner, LookAheadGoesStraightAsFarAsTheRouteAllowsAndNotThroughTheWall) {
  const std::vector<PlaceNode> places = grid_places();
  const RoutePlan plan = plan_to_goal(places, grid_edges_with_wall(), 3);
  // From 1 the route goes up 5, 9, then across the top and down (1, 5, 9, 10, 6, 2, 3): the
  // straight line reaches 9, two links on; the line to 10 would cut through the wall.
  EXPECT_EQ(look_ahead_place(places, plan, 1, 6, 0.5, {}), 9);
  EXPECT_EQ(look_ahead_place(places, plan, 1, 1, 0.5, {}), 5);  // one link: the next place
  EXPECT_EQ(look_ahead_place(places, plan, 3, 6, 0.5, {}), 3);  // at the goal
  for (int place = 0; place < static_cast<int>(places.size()); ++place) {
    const std::vector<int> route = plan.route_from(place);
    const int target = look_ahead_place(places, plan, place, 6, 0.5, {});
    if (place == plan.goal) continue;
    EXPECT_NE(std::find(route.begin() + 1, route.end(), target), route.end()) << place;
    EXPECT_FALSE(crosses_wall(places[place].position_m, places[target].position_m))
        << place << " -> " << target;
  }
  // The tolerance is what keeps the line on the route's side of the wall: with a whole spacing,
  // 9 (one spacing off the line from 1 to 10) no longer holds it back.
  const int loose = look_ahead_place(places, plan, 1, 6, 1.0, {});
  EXPECT_EQ(loose, 10);
  EXPECT_TRUE(crosses_wall(places[1].position_m, places[loose].position_m));
}

TEST(RoutePlanner, LookAheadKeepsClearOfLinksFoundBlocked) {
  // Two rows of six places 1 m apart, all neighbours linked: the route from 0 to the goal 5
  // runs straight along the lower row.
  std::vector<PlaceNode> places;
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 6; ++x) places.push_back({Eigen::Vector2d(x, y), 0.0});
  }
  const RoutePlan plan = plan_to_goal(places, lattice_neighbours(places, 1.5), 5);
  ASSERT_EQ(plan.route_from(0), (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(look_ahead_place(places, plan, 0, 10, 0.6, {}), 5);
  EXPECT_EQ(look_ahead_place(places, plan, 0, 3, 0.6, {}), 3);
  // The robot met furniture going from 3 up to 9, half a metre beside the line: the look-ahead
  // stops short of it. A blocked link a row away does not matter.
  EXPECT_EQ(look_ahead_place(places, plan, 0, 10, 0.6, {{3, 9}}), 2);
  EXPECT_EQ(look_ahead_place(places, plan, 0, 10, 0.6, {{9, 10}}), 5);
}

TEST(RoutePlanner, BadGoalOrEdgeIsAClearError) {
  EXPECT_THROW(plan_to_goal(grid_places(), grid_edges_with_wall(), 12), UsageError);
  EXPECT_THROW(plan_to_goal(grid_places(), {{0, 40}}, 0), UsageError);
}

TEST(RoutePlanner, LinksNamesReadBackAndAnyOtherIsAUsageError) {
  for (const RouteParams::Links links :
       {RouteParams::Links::kLattice, RouteParams::Links::kMotions, RouteParams::Links::kAuto}) {
    EXPECT_EQ(route_links_from_string(to_string(links)), links);
  }
  EXPECT_THROW(route_links_from_string("graph"), UsageError);
}

}  // namespace
}  // namespace omninav::navigation
