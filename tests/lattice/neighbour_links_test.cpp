// Lattice neighbour links (confirmed_links.hpp) of a map made by driving, judged against the
// renderer's poses: the README walkthrough's tour of the built-in room, organised
// (support/readme_room_tour.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>
#include <utility>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/lattice/confirmed_links.hpp"
#include "omninav/lattice/organise.hpp"
#include "support/readme_room_tour.hpp"

namespace omninav::lattice {
namespace {

constexpr double kSpacing_m = testing::kReadmeTourSpacing_m;

memory::VisualMemory driven_room_tour(bool odometry) {
  memory::VisualMemory map = testing::readme_room_tour(odometry);
  organise(map, {});
  return map;
}

struct Graph {
  std::vector<MeasuredLink> confirmed;
  std::vector<MeasuredLink> neighbours;
};

Graph links_of(const memory::VisualMemory& map) {
  std::vector<double> headings;
  std::vector<Eigen::Vector2d> positions;
  for (const std::optional<double>& heading : lattice_headings(map)) headings.push_back(*heading);
  for (std::size_t i = 0; i < map.place_count(); ++i) {
    positions.push_back(*map.place(i).lattice_position);
  }
  Graph graph;
  graph.confirmed = confirmed_links(map, headings, kSpacing_m, LinkParams{});
  graph.neighbours = lattice_neighbour_links(map, positions, graph.confirmed, LinkParams{});
  return graph;
}

Eigen::Vector2d true_position(const memory::VisualMemory& map, int place) {
  return map.place(place).truth->floor_position();
}

// Each link joins places truly side by side, at the true distance, in the true direction seen
// from each end (relative to the robot's heading there, which the place's image was taken at).
TEST(LatticeNeighbours, JoinPlacesTrulyBesideEachOtherInTheTrueDirection) {
  const memory::VisualMemory map = driven_room_tour(true);
  const Graph graph = links_of(map);
  ASSERT_FALSE(graph.neighbours.empty());  // how many: JoinTheLanesDrivenSideBySide
  std::set<std::pair<int, int>> confirmed;
  for (const MeasuredLink& link : graph.confirmed) confirmed.insert(link.places);
  std::vector<double> direction_errors;
  for (const MeasuredLink& link : graph.neighbours) {
    EXPECT_EQ(link.kind, LinkKind::kNeighbour);
    const auto [a, b] = link.places;
    EXPECT_FALSE(confirmed.count({a, b}) || confirmed.count({b, a})) << a << "-" << b;
    const Eigen::Vector2d step = true_position(map, b) - true_position(map, a);
    EXPECT_LE(step.norm(), 2.0 * kSpacing_m) << a << "-" << b;
    EXPECT_NEAR(link.length_m, step.norm(), kSpacing_m) << a << "-" << b;
    const double along = std::atan2(step.y(), step.x());
    direction_errors.push_back(std::abs(
        signed_difference(link.direction_at_first_rad, along - map.place(a).truth->heading_rad)));
    direction_errors.push_back(std::abs(signed_difference(
        link.direction_at_second_rad, along + kPi - map.place(b).truth->heading_rad)));
  }
  std::sort(direction_errors.begin(), direction_errors.end());
  std::cout << graph.neighbours.size() << " neighbour links; direction error median "
            << rad_to_deg(direction_errors[direction_errors.size() / 2]) << "°, 90th percentile "
            << rad_to_deg(direction_errors[direction_errors.size() * 9 / 10]) << "°, max "
            << rad_to_deg(direction_errors.back()) << "°\n";
  // The compass drifts by 14° over this tour; the links' directions come from the lattice and
  // the odometry, not from it. Measured: median 3.3°, 90th percentile 7.5°, max 9.3°.
  EXPECT_LT(rad_to_deg(direction_errors[direction_errors.size() / 2]), 5.0);
  EXPECT_LT(rad_to_deg(direction_errors[direction_errors.size() * 9 / 10]), 12.0);
}

// Places truly a lane apart are joined: a route between them goes across, not round the lanes'
// ends.
TEST(LatticeNeighbours, JoinTheLanesDrivenSideBySide) {
  const memory::VisualMemory map = driven_room_tour(true);
  const Graph graph = links_of(map);
  std::set<std::pair<int, int>> joined;
  for (const std::vector<MeasuredLink>* links : {&graph.confirmed, &graph.neighbours}) {
    for (const MeasuredLink& link : *links)
      joined.insert(std::minmax(link.places.first, link.places.second));
  }
  int beside = 0, linked = 0, linked_before = 0;
  std::set<std::pair<int, int>> confirmed;
  for (const MeasuredLink& link : graph.confirmed)
    confirmed.insert(std::minmax(link.places.first, link.places.second));
  for (int a = 0; a < static_cast<int>(map.place_count()); ++a) {
    for (int b = a + 1; b < static_cast<int>(map.place_count()); ++b) {
      if ((true_position(map, b) - true_position(map, a)).norm() > 1.1 * kSpacing_m) continue;
      ++beside;
      linked += joined.count({a, b}) ? 1 : 0;
      linked_before += confirmed.count({a, b}) ? 1 : 0;
    }
  }
  std::cout << beside << " pairs of places truly within 1.1 spacings: " << linked_before
            << " joined by travelled links and revisits, " << linked << " with the neighbours\n";
  EXPECT_GE(linked, 0.8 * beside);
  EXPECT_GT(linked, linked_before);
}

// A map without odometry is organised by the spring model, from appearance alone: its lattice
// may put look-alikes side by side, and gives no neighbour links.
TEST(LatticeNeighbours, NoneWithoutOdometry) {
  const memory::VisualMemory map = driven_room_tour(false);
  EXPECT_TRUE(links_of(map).neighbours.empty());
}

TEST(LatticeNeighbours, PositionsMustBeOnePerPlace) {
  const memory::VisualMemory map = driven_room_tour(true);
  EXPECT_THROW(lattice_neighbour_links(map, {Eigen::Vector2d::Zero()}, {}, LinkParams{}),
               UsageError);
}

}  // namespace
}  // namespace omninav::lattice
