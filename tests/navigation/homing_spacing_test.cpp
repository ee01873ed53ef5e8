// Homing's distances come from the map's spacing, measured when navigation starts
// (navigator.homing_step_spacings, homing_stop_spacings): on rendered grids of the built-in
// room 10 cm and 60 cm apart, the goal image seen from its own pose seems nearer than the
// derived stop and seen from a place one true spacing away seems farther, so homing neither
// stops a spacing short of the goal nor walks on past it. The distances in metres chosen on
// the room's 30 cm grid (0.15 m) stop a 10 cm grid's homing a spacing and more from the goal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "omninav/core/angles.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/navigation/homing.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/room.hpp"
#include "support/rendered_map.hpp"

namespace omninav::navigation {
namespace {

constexpr int kNx = 5, kNy = 4;

// A point of the floor with at least `clearance_m` free round it, the first on a 10 cm scan.
std::optional<Eigen::Vector2d> open_floor(const sim::World& world, double clearance_m) {
  for (double x = world.floor.min_x_m; x <= world.floor.max_x_m; x += 0.1) {
    for (double y = world.floor.min_y_m; y <= world.floor.max_y_m; y += 0.1) {
      if (world.is_free(x, y, clearance_m)) return Eigen::Vector2d(x, y);
    }
  }
  return std::nullopt;
}

struct Spaced {
  double spacing_m;
};

class HomingSpacing : public ::testing::TestWithParam<Spaced> {};

TEST_P(HomingSpacing, TheDerivedStopLiesBetweenTheGoalAndOneSpacingFromIt) {
  const double spacing_m = GetParam().spacing_m;
  const sim::World world = sim::make_room(sim::RoomParams{});
  sim::RenderParams render;
  render.geometry.width_px = 180;
  render.geometry.height_px = 24;
  const sim::Renderer renderer(world, render);
  // The goal and every view of it below stand in the open: 1.2 spacings of free floor round
  // the grid's middle.
  const std::optional<Eigen::Vector2d> middle = open_floor(world, 1.2 * spacing_m + 0.1);
  ASSERT_TRUE(middle) << "no open floor for a " << spacing_m << " m grid";
  const double cx_m = middle->x(), cy_m = middle->y();
  const double x0 = cx_m - 0.5 * (kNx - 1) * spacing_m, y0 = cy_m - 0.5 * (kNy - 1) * spacing_m;
  const std::string grid = "grid:x0=" + std::to_string(x0) + ",y0=" + std::to_string(y0) +
                           ",nx=" + std::to_string(kNx) + ",ny=" + std::to_string(kNy) +
                           ",spacing_m=" + std::to_string(spacing_m) + ",z_m=1";
  memory::VisualMemory memory = testing::rendered_grid_map(world, render, grid, "room");
  testing::set_truth_lattice(memory);
  const memory::Localiser localiser(memory, memory::LocalisationParams{});
  signature::SignatureExtractor extractor(memory.parameters().signature);
  const GoalNavigationSetup setup =
      goal_navigation_setup(memory, memory_localiser(localiser, extractor), RouteParams{},
                            NavigatorParams{}, LinkParams{}, BeliefParams{}, SteeringParams{});
  const NavigatorParams defaults;
  // The metres follow the rendered grid's spacing.
  EXPECT_NEAR(setup.navigator.homing_stop_m, defaults.homing_stop_spacings * spacing_m,
              0.02 * spacing_m);
  EXPECT_NEAR(setup.navigator.homing_step_m, defaults.homing_step_spacings * spacing_m,
              0.02 * spacing_m);

  // The goal: a pose inside the grid, off its places; its image, and views of it from its own
  // pose (turned) and from one true spacing away in four directions.
  const CameraPose goal{cx_m + 0.2 * spacing_m, cy_m + 0.3 * spacing_m, 1.0, 0.4, 0.0, 0.0};
  const GoalHoming homing = goal_homing(renderer.render(goal), setup.homing);
  CameraPose turned = goal;
  turned.heading_rad += 1.3;
  EXPECT_LT(homing(renderer.render(turned)).distance_m, setup.navigator.homing_stop_m);
  double nearest_m = std::numeric_limits<double>::infinity();
  for (int side = 0; side < 4; ++side) {
    CameraPose away = goal;
    away.x_m += spacing_m * std::cos(0.5 * kPi * side + 0.3);
    away.y_m += spacing_m * std::sin(0.5 * kPi * side + 0.3);
    nearest_m = std::min(nearest_m, homing(renderer.render(away)).distance_m);
  }
  EXPECT_GT(nearest_m, setup.navigator.homing_stop_m) << "spacing " << spacing_m << " m";
  if (spacing_m < 0.15) {
    // The room's metres: a view a whole spacing from the goal already seems near enough.
    EXPECT_LT(nearest_m, NavigatorParams{}.homing_stop_m);
  }
}

INSTANTIATE_TEST_SUITE_P(RenderedGrids, HomingSpacing, ::testing::Values(Spaced{0.1}, Spaced{0.6}),
                         [](const ::testing::TestParamInfo<Spaced>& info) {
                           return "Every" +
                                  std::to_string(
                                      static_cast<int>(std::lround(100.0 * info.param.spacing_m))) +
                                  "cm";
                         });

}  // namespace
}  // namespace omninav::navigation
