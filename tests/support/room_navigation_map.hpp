#pragma once
// A map of rendered panoramas on a 30 cm grid of the built-in room, localised by the memory's
// hierarchical localisation, for the tests of navigation with real recognition
// (tests/navigation, tests/evaluation). The lattice is not the spring model's (libs/lattice
// has its own tests): each place's lattice position is its true position, turned into the
// lattice frame (the first place's heading along +x), so that these tests isolate planning,
// recognition and control. Success is judged against the renderer's poses.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/room.hpp"
#include "support/rendered_map.hpp"

namespace omninav::testing {

constexpr double kRoomGridSpacing_m = 0.3;

// A panorama of the grid with the pose it was rendered at.
struct StoredView {
  cv::Mat panorama;
  CameraPose pose;
};

// The map and everything the navigator needs, built once for the suite (rendering and
// signatures of ~80 panoramas).
struct RoomMap {
  sim::World world;
  sim::RenderParams render;
  std::unique_ptr<sim::Renderer> renderer;
  memory::VisualMemory memory;
  std::vector<StoredView> grid;  // the panoramas the places were made from, with their poses
  std::vector<navigation::PlaceNode> places;
  std::unique_ptr<memory::Localiser> localiser;
  std::unique_ptr<signature::SignatureExtractor> extractor;
  navigation::PanoramaLocaliser localise;
};

// A 10 × 8 grid at 30 cm (the reference grid of the navigation target), points inside furniture
// left out.
inline RoomMap* build_room_map() {
  auto map = new RoomMap;
  map->world = sim::make_room(sim::RoomParams{});
  map->render.geometry.width_px = 180;
  map->render.geometry.height_px = 24;
  map->renderer = std::make_unique<sim::Renderer>(map->world, map->render);
  // Headings from the truth: these tests isolate navigation from the visual compass too.
  memory::ExplorationParams exploration;
  exploration.heading_source = memory::HeadingPolicy::kTruth;
  memory::Explorer explorer(map->memory, exploration, "rendered grid", "test",
                            memory::FrameOrder::kUnordered);  // a grid database, not a stream
  int index = 0;
  for (int iy = 0; iy < 8; ++iy) {
    for (int ix = 0; ix < 10; ++ix) {
      const double x = 1.2 + kRoomGridSpacing_m * ix, y = 1.0 + kRoomGridSpacing_m * iy;
      if (!map->world.is_free(x, y, 0.05)) continue;
      io::Frame frame;
      frame.index = index++;
      frame.truth = CameraPose{x, y, 1.0, deg_to_rad(20.0), 0.0, 0.0};
      frame.image = map->renderer->render(*frame.truth);
      frame.source = "grid " + std::to_string(ix) + "," + std::to_string(iy);
      explorer.add_place(frame);
      map->grid.push_back({frame.image, *frame.truth});
    }
  }
  // A grid database states its spacing: the navigator links grid neighbours by it.
  map->memory.set_grid_spacing_m(kRoomGridSpacing_m);
  // Lattice from the truth, in the lattice frame: origin at the first place, its heading +x.
  set_truth_lattice(map->memory);
  map->places = navigation::places_from_memory(map->memory);
  map->localiser = std::make_unique<memory::Localiser>(map->memory, memory::LocalisationParams{});
  map->extractor =
      std::make_unique<signature::SignatureExtractor>(map->memory.parameters().signature);
  map->localise = navigation::memory_localiser(*map->localiser, *map->extractor);
  return map;
}

class RoomNavigation : public ::testing::Test {
 public:
  static void SetUpTestSuite() {
    if (!map_) map_ = build_room_map();
  }
  static const RoomMap& map() { return *map_; }
  static double limit() { return navigation::match_limit(map().memory, navigation::RouteParams{}); }
  static navigation::HomingScale homing() {
    return navigation::homing_scale(map().memory, map().places);
  }
  // Navigation to goal images on the map with the default settings.
  static navigation::GoalNavigationSetup setup() {
    return navigation::goal_navigation_setup(
        map().memory, map().localise, navigation::RouteParams{}, navigation::NavigatorParams{},
        navigation::LinkParams{}, navigation::BeliefParams{},
        navigation::SteeringParams{{}, map().render.geometry});
  }
  // How far place `place` lies from (x, y) by truth.
  static double place_distance_m(std::size_t place, double x_m, double y_m) {
    const CameraPose& pose = map().grid[place].pose;
    return std::hypot(pose.x_m - x_m, pose.y_m - y_m);
  }
  // The place nearest to (x, y) by truth.
  static int nearest_place(double x_m, double y_m) {
    int best = 0;
    for (std::size_t i = 0; i < map().grid.size(); ++i) {
      if (place_distance_m(i, x_m, y_m) < place_distance_m(best, x_m, y_m)) {
        best = static_cast<int>(i);
      }
    }
    return best;
  }

  inline static RoomMap* map_ = nullptr;
};

}  // namespace omninav::testing
