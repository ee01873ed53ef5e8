// Where evaluate puts its routes and queries, and how far outside the mapped area a robot went,
// against constructed worlds and point sets.
#include <gtest/gtest.h>

#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/evaluation/evaluate.hpp"

namespace omninav::evaluation {
namespace {

sim::World floor_only(double size_x_m, double size_y_m) {
  sim::World world;
  world.name = "constructed";
  world.floor = {0.0, 0.0, size_x_m, size_y_m};
  return world;
}

TEST(DistanceOutside, IsZeroInsideAndTheDistanceToTheNearestEdgeOutside) {
  const std::vector<Eigen::Vector2d> square = {
      {0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}, {0.5, 0.5}};
  const std::vector<Eigen::Vector2d> hull = convex_hull(square);
  EXPECT_EQ(hull.size(), 4u);  // the middle point is not on the hull
  EXPECT_EQ(distance_outside(hull, {0.5, 0.5}), 0.0);
  EXPECT_EQ(distance_outside(hull, {0.0, 0.3}), 0.0);  // on an edge
  EXPECT_NEAR(distance_outside(hull, {3.0, 0.5}), 2.0, 1e-12);
  EXPECT_NEAR(distance_outside(hull, {0.5, -0.25}), 0.25, 1e-12);
  EXPECT_NEAR(distance_outside(hull, {2.0, 2.0}), std::sqrt(2.0), 1e-12);  // past a corner
}

// A grid of places, as evaluate maps: the hull is its four corners, counter-clockwise, none of
// the points along its edges.
TEST(ConvexHull, OfAGridIsItsCornersCounterClockwise) {
  std::vector<Eigen::Vector2d> grid;
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) grid.emplace_back(0.3 * x, 0.3 * y);
  }
  const std::vector<Eigen::Vector2d> hull = convex_hull(grid);
  ASSERT_EQ(hull.size(), 4u);
  double twice_area = 0.0;  // positive when counter-clockwise
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d& a = hull[i];
    const Eigen::Vector2d& b = hull[(i + 1) % hull.size()];
    twice_area += a.x() * b.y() - b.x() * a.y();
  }
  EXPECT_NEAR(twice_area, 2 * 0.9 * 0.6, 1e-12);
}

TEST(DistanceOutside, IsTheSameWhicheverWayTheHullTurns) {
  const std::vector<Eigen::Vector2d> clockwise = {{0.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}, {1.0, 0.0}};
  EXPECT_EQ(distance_outside(clockwise, {0.2, 0.7}), 0.0);
  EXPECT_NEAR(distance_outside(clockwise, {-1.5, 0.5}), 1.5, 1e-12);
}

TEST(DistanceOutside, ALineOfPlacesIsASegmentAndOnePlaceAPoint) {
  const std::vector<Eigen::Vector2d> line = convex_hull({{0.0, 0.0}, {2.0, 0.0}});
  EXPECT_NEAR(distance_outside(line, {1.0, 0.5}), 0.5, 1e-12);
  EXPECT_NEAR(distance_outside(line, {3.0, 0.0}), 1.0, 1e-12);
  EXPECT_NEAR(distance_outside(convex_hull({{1.0, 1.0}}), {4.0, 5.0}), 5.0, 1e-12);
}

TEST(PlanLayout, CentresTheGridOnTheFloorAndShrinksItToFit) {
  const sim::World world = floor_only(6.0, 2.0);
  const WorldLayout layout = plan_layout(world, 10, 8, 0.3, 1.0, 0.15);
  EXPECT_EQ(layout.nx, 10);
  // 2 m deep with a spacing's margin on each side: at most 1.4 m of grid, 5 rows of 0.3 m.
  EXPECT_EQ(layout.ny, 5);
  EXPECT_NEAR(layout.first_point.x() + (layout.nx - 1) * 0.3 / 2, 3.0, 1e-12);
  EXPECT_NEAR(layout.first_point.y() + (layout.ny - 1) * 0.3 / 2, 1.0, 1e-12);
  EXPECT_GE(layout.first_point.y(), 0.3 - 1e-12);
  EXPECT_LE(layout.first_point.y() + (layout.ny - 1) * 0.3, 1.7 + 1e-12);
}

TEST(PlanLayout, TheCircleIsFreeOfObstaclesAndAsLargeAsAllowed) {
  sim::World world = floor_only(6.0, 6.0);
  world.obstacles.push_back({2.8, 2.8, 3.2, 3.2});  // a box in the middle
  const WorldLayout layout = plan_layout(world, 10, 8, 0.3, 1.0, 0.15);
  EXPECT_DOUBLE_EQ(layout.circle_radius_m, 1.0);
  EXPECT_TRUE(world.is_free(layout.centre.x(), layout.centre.y(), 0.15));
  for (int k = 0; k < 360; ++k) {
    const double angle = deg_to_rad(k);
    EXPECT_TRUE(
        world.is_free(layout.centre.x() + std::cos(angle), layout.centre.y() + std::sin(angle)))
        << k;
  }
}

TEST(PlanLayout, ASmallRoomGetsASmallerCircle) {
  const sim::World world = floor_only(1.2, 1.2);
  const WorldLayout layout = plan_layout(world, 10, 8, 0.3, 1.0, 0.15);
  EXPECT_LE(layout.circle_radius_m, 0.45 + 1e-12);  // 0.6 minus the clearance
  EXPECT_GT(layout.circle_radius_m, 0.3);
}

TEST(PlanLayout, AFloorWithoutRoomForAGridIsAnInputError) {
  EXPECT_THROW(plan_layout(floor_only(0.5, 5.0), 10, 8, 0.3, 1.0, 0.15), InputError);
  sim::World blocked = floor_only(3.0, 3.0);
  blocked.obstacles.push_back({0.0, 0.0, 3.0, 3.0});
  EXPECT_THROW(plan_layout(blocked, 10, 8, 0.3, 1.0, 0.15), InputError);
}

TEST(RandomFreePoses, AreSeededFreeAndInsideTheRectangle) {
  sim::World world = floor_only(6.0, 5.0);
  world.obstacles.push_back({2.0, 2.0, 3.0, 3.0});
  const std::vector<CameraPose> poses =
      random_free_poses(world, {1.5, 1.5}, {3.5, 3.5}, 200, 7, 0.4);
  ASSERT_EQ(poses.size(), 200u);
  double min_heading = kPi, max_heading = -kPi;
  for (const CameraPose& pose : poses) {
    EXPECT_TRUE(world.is_free(pose.x_m, pose.y_m, 0.05));
    EXPECT_GE(pose.x_m, 1.5);
    EXPECT_LE(pose.x_m, 3.5);
    EXPECT_GE(pose.y_m, 1.5);
    EXPECT_LE(pose.y_m, 3.5);
    EXPECT_EQ(pose.z_m, 0.4);
    min_heading = std::min(min_heading, pose.heading_rad);
    max_heading = std::max(max_heading, pose.heading_rad);
  }
  EXPECT_LT(min_heading, -2.5);  // headings cover the circle
  EXPECT_GT(max_heading, 2.5);
  const std::vector<CameraPose> again =
      random_free_poses(world, {1.5, 1.5}, {3.5, 3.5}, 200, 7, 0.4);
  const std::vector<CameraPose> other =
      random_free_poses(world, {1.5, 1.5}, {3.5, 3.5}, 200, 8, 0.4);
  EXPECT_EQ(again.front().x_m, poses.front().x_m);
  EXPECT_EQ(again.back().heading_rad, poses.back().heading_rad);
  EXPECT_NE(other.front().x_m, poses.front().x_m);
}

TEST(RightRegionShare, CountsQueriesWhoseBestPlaceIsInTheirRegion) {
  sim::World world = floor_only(8.0, 4.0);
  world.regions = {{"room 1", {0.0, 0.0, 3.9, 4.0}}, {"room 2", {4.1, 0.0, 8.0, 4.0}}};
  // Three queries in room 1 (two found there, one in room 2), one in room 2 found there, one
  // in the doorway between (no region: left out).
  const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> localised = {
      {{1.0, 1.0}, {1.2, 1.1}},
      {{2.0, 3.0}, {2.3, 3.0}},
      {{3.5, 2.0}, {4.5, 2.0}},
      {{6.0, 2.0}, {6.1, 2.2}},
      {{4.0, 2.0}, {1.0, 1.0}}};
  const std::optional<double> share = right_region_share(world, localised);
  ASSERT_TRUE(share);
  EXPECT_DOUBLE_EQ(*share, 3.0 / 4.0);
  // A best place in a doorway is in no room: not the right one.
  EXPECT_DOUBLE_EQ(*right_region_share(world, {{{1.0, 1.0}, {4.0, 1.0}}}), 0.0);
}

TEST(RightRegionShare, IsNothingInAWorldWithoutRegions) {
  EXPECT_FALSE(right_region_share(floor_only(5.0, 5.0), {{{1.0, 1.0}, {1.0, 1.0}}}));
}

}  // namespace
}  // namespace omninav::evaluation
