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

// The grid's links, 1 m long, each with its direction from either end relative to that place's
// heading (the places' headings in `places`).
std::vector<MeasuredLink> grid_links_with_wall(const std::vector<PlaceNode>& places) {
  std::vector<MeasuredLink> links;
  const auto link = [&](int a, int b, double direction) {
    links.push_back({{a, b},
                     1.0,
                     wrap_angle(direction - places[a].heading_rad),
                     wrap_angle(direction + kPi - places[b].heading_rad),
                     LinkKind::kGrid});
  };
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) {
      const int place = 4 * y + x;
      if (x + 1 < 4 && !(x == 1 && y < 2)) link(place, place + 1, 0.0);
      if (y + 1 < 3) link(place, place + 4, 0.5 * kPi);
    }
  }
  return links;
}

TEST(RoutePlanner, ReturnsTheShortestPathRoundTheWall) {
  const RoutePlan plan = plan_to_goal(grid_places(), grid_links_with_wall(grid_places()), 3);
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
  const RoutePlan plan = plan_to_goal(places, grid_links_with_wall(places), 3);
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
  const RoutePlan plan = plan_to_goal(places, grid_links_with_wall(places), 0);
  EXPECT_FALSE(plan.reaches_goal(12));
  EXPECT_TRUE(plan.route_from(12).empty());
  EXPECT_TRUE(plan.reaches_goal(11));
}

TEST(RoutePlanner, BadGoalOrEdgeIsAClearError) {
  EXPECT_THROW(plan_to_goal(grid_places(), grid_links_with_wall(grid_places()), 12), UsageError);
  EXPECT_THROW(plan_to_goal(grid_places(), {{{0, 40}, 1.0, 0.0, 0.0, LinkKind::kGrid}}, 0),
               UsageError);
}

}  // namespace
}  // namespace omninav::navigation
