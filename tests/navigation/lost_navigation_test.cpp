// A robot placed off the map, in rendered worlds of several families (the built-in room, the
// office, the field seen from 10 cm): it finds itself lost and either comes onto the map and
// reaches its goal, or goes back to where it started and stops, inside its step budget; it never
// drives away. Judged against the renderer's poses: the mapped area is the convex hull of the
// grid's true positions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "omninav/evaluation/evaluate.hpp"
#include "omninav/evaluation/robot_worlds.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/navigation/goal_navigation.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "omninav/sim/world_loader.hpp"
#include "support/rendered_map.hpp"

namespace omninav::navigation {
namespace {

constexpr double kSpacing_m = 0.3;
constexpr int kNx = 6, kNy = 5;

struct Family {
  std::string name;
  std::string spec;  // load_world's
  double z_m;        // camera height
};

// A 6 × 5 grid map at 30 cm in the middle of the world's floor, its lattice the truth (these
// tests isolate navigation from the spring model), and everything the navigator needs.
struct FamilyMap {
  explicit FamilyMap(const Family& family)
      : world(sim::load_world(family.spec, sim::WorldsConfig{})), z_m(family.z_m) {
    render.geometry.width_px = 180;
    render.geometry.height_px = 24;
    renderer = std::make_unique<sim::Renderer>(world, render);
    const double cx = 0.5 * (world.floor.min_x_m + world.floor.max_x_m);
    const double cy = 0.5 * (world.floor.min_y_m + world.floor.max_y_m);
    x0 = cx - 0.5 * (kNx - 1) * kSpacing_m;
    y0 = cy - 0.5 * (kNy - 1) * kSpacing_m;
    const std::string grid = "grid:x0=" + std::to_string(x0) + ",y0=" + std::to_string(y0) +
                             ",nx=" + std::to_string(kNx) + ",ny=" + std::to_string(kNy) +
                             ",spacing_m=" + std::to_string(kSpacing_m) +
                             ",z_m=" + std::to_string(z_m);
    memory = testing::rendered_grid_map(world, render, grid, family.name);
    testing::set_truth_lattice(memory);
    std::vector<Eigen::Vector2d> mapped;
    for (std::size_t i = 0; i < memory.place_count(); ++i) {
      mapped.push_back(memory.place(i).truth->floor_position());
    }
    hull = evaluation::convex_hull(mapped);
    localiser = std::make_unique<memory::Localiser>(memory, memory::LocalisationParams{});
    extractor = std::make_unique<signature::SignatureExtractor>(memory.parameters().signature);
    setup = goal_navigation_setup(memory, memory_localiser(*localiser, *extractor), RouteParams{},
                                  NavigatorParams{});
  }

  double outside_m(const CameraPose& pose) const {
    return evaluation::distance_outside(hull, pose.floor_position());
  }

  sim::World world;
  double z_m;
  sim::RenderParams render;
  std::unique_ptr<sim::Renderer> renderer;
  double x0 = 0.0, y0 = 0.0;
  memory::VisualMemory memory;
  std::vector<Eigen::Vector2d> hull;
  std::unique_ptr<memory::Localiser> localiser;
  std::unique_ptr<signature::SignatureExtractor> extractor;
  GoalNavigationSetup setup;
};

struct Outcome {
  NavigationResult result;
  CameraPose end;
  double farthest_outside_m = 0.0;
};

// Drives a virtual robot from `start` to the goal image rendered at the grid's middle.
Outcome navigate_from(const FamilyMap& map, const CameraPose& start) {
  sim::VirtualRobot robot(map.world, start, sim::RobotParams{});
  evaluation::RenderedWorld body(robot, *map.renderer);
  const CameraPose goal{map.x0 + 0.5 * (kNx - 1) * kSpacing_m + 0.1,
                        map.y0 + 0.5 * (kNy - 1) * kSpacing_m,
                        map.z_m,
                        0.3,
                        0.0,
                        0.0};
  Outcome outcome;
  outcome.result = navigate_to_image(body, map.renderer->render(goal), "goal", map.setup).result;
  outcome.end = robot.pose();
  outcome.farthest_outside_m = map.outside_m(outcome.end);
  for (const NavigationStep& step : outcome.result.steps) {
    outcome.farthest_outside_m = std::max(outcome.farthest_outside_m, map.outside_m(step.truth));
  }
  return outcome;
}

class LostNavigation : public ::testing::TestWithParam<Family> {};

TEST_P(LostNavigation, ARobotOffTheMapFindsItselfLostAndNeverDrivesAway) {
  const FamilyMap map(GetParam());
  const NavigatorParams& params = map.setup.navigator;
  // `spacings` outside the grid, off the middle of its west, east, south or north edge (the
  // first where the floor is free), facing away from it: floor the map never saw.
  const auto start_at = [&](double spacings) {
    const double cx = map.x0 + 0.5 * (kNx - 1) * kSpacing_m;
    const double cy = map.y0 + 0.5 * (kNy - 1) * kSpacing_m;
    const double out_x = 0.5 * (kNx - 1) * kSpacing_m + spacings * kSpacing_m;
    const double out_y = 0.5 * (kNy - 1) * kSpacing_m + spacings * kSpacing_m;
    for (const auto& [dx, dy] : std::vector<std::pair<double, double>>{
             {-out_x, 0.0}, {out_x, 0.0}, {0.0, -out_y}, {0.0, out_y}}) {
      if (map.world.is_free(cx + dx, cy + dy, sim::RobotParams{}.radius_m + 0.05)) {
        return CameraPose{cx + dx, cy + dy, map.z_m, std::atan2(dy, dx), 0.0, 0.0};
      }
    }
    ADD_FAILURE() << "no free start " << spacings << " spacings off the grid";
    return CameraPose{cx - out_x, cy, map.z_m, 0.0, 0.0, 0.0};
  };

  // Five spacings out the robot recognises no place (what this test needs: its view differs
  // from every place by more than the map's recognition limit)...
  const CameraPose far = start_at(5.0);
  const memory::Localisation at_start = map.setup.localise(map.renderer->render(far));
  ASSERT_FALSE(at_start.best.empty());
  const memory::PlaceMatch& best = at_start.best.front();
  ASSERT_GT(best.dissimilarity_per_value, map.setup.place_recognition_limits.empty()
                                              ? map.setup.recognition_limit
                                              : map.setup.place_recognition_limits[best.place]);
  const Outcome from_far = navigate_from(map, far);
  // ... finds itself lost, and then comes onto the map and reaches the goal, or goes back and
  // stops, long before its step budget is spent.
  EXPECT_GE(from_far.result.lost_events, 1);
  EXPECT_TRUE(from_far.result.reached || from_far.result.gave_up);
  EXPECT_LT(static_cast<int>(from_far.result.steps.size()), params.max_steps / 2);
  // It ends no farther out than it started (the return is by dead reckoning: a few cm of
  // noise), and never strayed farther than the views that found it lost.
  EXPECT_LT(map.outside_m(from_far.end), map.outside_m(far) + 0.5 * kSpacing_m);
  EXPECT_LT(from_far.farthest_outside_m,
            map.outside_m(far) + 2 * params.lost_views * params.step_m + 0.05);

  // One spacing out, whether it recognises the map from there or not, it ends within one
  // spacing of the mapped area, give or take the few centimetres of its dead reckoning back to
  // its start.
  const Outcome from_near = navigate_from(map, start_at(1.0));
  EXPECT_TRUE(from_near.result.reached || from_near.result.gave_up);
  EXPECT_LT(map.outside_m(from_near.end), 1.2 * kSpacing_m);
  EXPECT_LT(static_cast<int>(from_near.result.steps.size()), params.max_steps);
}

INSTANTIATE_TEST_SUITE_P(Families, LostNavigation,
                         ::testing::Values(Family{"room", "room", 1.0},
                                           Family{"office", "office", 1.0},
                                           Family{"field", "field", 0.1}),
                         [](const ::testing::TestParamInfo<Family>& info) {
                           return info.param.name;
                         });

}  // namespace
}  // namespace omninav::navigation
