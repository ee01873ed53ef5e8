// The confirmed links of a rendered grid of the built-in room, judged against the renderer's
// poses (tests/support/room_navigation_map.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "support/room_navigation_map.hpp"

namespace omninav::testing {
namespace {

using navigation::LinkKind;
using navigation::MeasuredLink;

TEST_F(RoomNavigation, GridLinksJoinNeighboursInTheDatabasesDirection) {
  const std::vector<MeasuredLink> links =
      navigation::map_links(map().memory, map().places, navigation::LinkParams{});
  ASSERT_FALSE(links.empty());
  std::set<int> linked;
  for (const MeasuredLink& link : links) {
    EXPECT_EQ(link.kind, LinkKind::kGrid);
    const auto [a, b] = link.places;
    const CameraPose& pa = map().grid[a].pose;
    const CameraPose& pb = map().grid[b].pose;
    const double distance = std::hypot(pb.x_m - pa.x_m, pb.y_m - pa.y_m);
    // Grid neighbours (the 8-neighbourhood), or the nearest pair joining two pieces.
    EXPECT_LE(distance, 3.0 * kRoomGridSpacing_m) << a << "-" << b;
    EXPECT_NEAR(link.length_m, distance, 1e-9);
    // The direction at each end, relative to that place's heading, is the true one.
    const double direction = std::atan2(pb.y_m - pa.y_m, pb.x_m - pa.x_m);
    EXPECT_NEAR(
        signed_difference(link.direction_at_first_rad + map().places[a].heading_rad, direction),
        0.0, 1e-6);
    EXPECT_NEAR(signed_difference(link.direction_at_second_rad + map().places[b].heading_rad,
                                  wrap_angle(direction + kPi)),
                0.0, 1e-6);
    linked.insert(a);
    linked.insert(b);
  }
  // Every place can be planned to and from.
  EXPECT_EQ(linked.size(), map().memory.place_count());
  const navigation::RoutePlan plan = navigation::plan_to_goal(map().places, links, 0);
  for (std::size_t place = 0; place < map().places.size(); ++place) {
    EXPECT_TRUE(plan.reaches_goal(static_cast<int>(place))) << place;
  }
}

TEST_F(RoomNavigation, GridChecksThatNoPairPassesStillLeaveOneConnectedGraph) {
  navigation::LinkParams strict;
  strict.grid_direction_deg = 0.0;  // no fitted motion agrees that exactly
  const std::vector<MeasuredLink> links = navigation::map_links(map().memory, map().places, strict);
  // The pieces are joined, by as few links as a tree needs.
  EXPECT_EQ(links.size(), map().memory.place_count() - 1);
  const navigation::RoutePlan plan = navigation::plan_to_goal(map().places, links, 0);
  for (std::size_t place = 0; place < map().places.size(); ++place) {
    EXPECT_TRUE(plan.reaches_goal(static_cast<int>(place))) << place;
  }
}

// Values set in code, as Python's writable fields set them, are refused by the algorithm that
// takes them as the YAML loader refuses them in navigation.yaml, naming the key (the check() of
// LinkParams, RouteParams and NavigatorParams).
TEST(NavigationParams, OutOfRangeAreRefusedNamingTheKey) {
  const memory::VisualMemory memory{memory::MapParameters{}};
  const auto refusal = [](const std::function<void()>& action) -> std::string {
    try {
      action();
    } catch (const UsageError& error) {
      return error.what();
    }
    return "";
  };
  navigation::LinkParams links;
  links.revisit_ratio = 0.0;
  EXPECT_NE(refusal([&] {
              lattice::confirmed_links(memory, {}, 0.3, links);
            }).find("links.revisit_ratio"),
            std::string::npos);
  navigation::RouteParams route;
  route.match_dissimilarity_ratio = 1000.0;
  EXPECT_NE(refusal([&] {
              navigation::match_limit(memory, route);
            }).find("route.match_dissimilarity_ratio"),
            std::string::npos);
  navigation::NavigatorParams navigator;
  navigator.max_steps = 0;
  EXPECT_NE(refusal([&] {
              navigation::goal_navigation_setup(memory, {}, {}, navigator, {}, {}, {});
            }).find("navigator.max_steps"),
            std::string::npos);
}

}  // namespace
}  // namespace omninav::testing
