// Exploration's new-place threshold "auto" (exploration.hpp) against ground truth in worlds of
// four families: a zig-zag stream rendered over a rectangle of the world, explored with
// new_place_dissimilarity auto, and the places' spacing measured from their true positions
// (metres of the stream per place). The share of the plateau was chosen across the zoo for the
// papers' 30 cm (config/memory.yaml); here every world must come within a factor kBand of it,
// where the room's fixed 1.5 grey levels spaces places 8 cm apart in the room and 1 m apart in
// the field.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "omninav/io/frame.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/trajectory.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::memory {
namespace {

struct Spacing {
  double auto_m = 0.0;   // metres of the stream per place (their true positions), auto
  double fixed_m = 0.0;  // the same with the room's fixed 1.5
  int auto_places = 0;
};

Spacing spacing_in(const std::string& spec, const std::string& zigzag) {
  const sim::World world = sim::load_world(spec, sim::WorldsConfig{});
  sim::RenderParams render;
  render.geometry.width_px = 360;
  render.geometry.height_px = 45;
  const sim::Renderer renderer(world, render);
  const sim::Trajectory stream = sim::make_trajectory(zigzag, world);
  std::vector<io::Frame> frames;
  double travelled_m = 0.0;
  for (std::size_t i = 0; i < stream.poses.size(); ++i) {
    if (i > 0) {
      travelled_m += std::hypot(stream.poses[i].pose.x_m - stream.poses[i - 1].pose.x_m,
                                stream.poses[i].pose.y_m - stream.poses[i - 1].pose.y_m);
    }
    io::Frame frame;
    frame.index = static_cast<int>(i);
    frame.truth = stream.poses[i].pose;
    frame.image = renderer.render(*frame.truth);
    frame.source = spec + "#" + std::to_string(i);
    frames.push_back(std::move(frame));
  }

  const auto explore = [&](bool automatic) {
    VisualMemory memory{MapParameters{}};
    ExplorationParams params;
    params.new_place_dissimilarity = automatic ? std::nullopt : std::optional<double>(1.5);
    params.heading_source = HeadingPolicy::kNone;
    params.thumbnail_width_px = 8;
    Explorer explorer(memory, params, spec, "zoo_exploration_test.cpp");
    for (const io::Frame& frame : frames) explorer.add(frame);
    // Metres of the stream per place after the first: the mean spacing along the way.
    const int places = static_cast<int>(memory.place_count());
    return std::pair{travelled_m / std::max(1, places - 1), places};
  };

  Spacing spacing;
  std::tie(spacing.auto_m, spacing.auto_places) = explore(true);
  spacing.fixed_m = explore(false).first;
  std::cout << spec << ": auto " << spacing.auto_m << " m (" << spacing.auto_places << " places of "
            << frames.size() << " frames), fixed 1.5: " << spacing.fixed_m << " m\n";
  return spacing;
}

// A zig-zag of 4 rows over a 2.1 × 1.2 m rectangle at the height z_m, a frame every 4 cm.
std::string zigzag(double x0_m, double y0_m, double z_m) {
  return "zigzag:x0=" + std::to_string(x0_m) + ",y0=" + std::to_string(y0_m) +
         ",x1=" + std::to_string(x0_m + 2.1) + ",y1=" + std::to_string(y0_m + 1.2) +
         ",rows=4,speed_m_s=0.2,fps=5,z_m=" + std::to_string(z_m);
}

// The target and the band: auto's spacing within kBand of 30 cm either way (0.12-0.75 m).
constexpr double kTarget_m = 0.3;
constexpr double kBand = 2.5;

bool in_band(double spacing_m) {
  return spacing_m > kTarget_m / kBand && spacing_m < kTarget_m * kBand;
}

void expect_in_band(const Spacing& s) {
  EXPECT_TRUE(in_band(s.auto_m)) << s.auto_m << " m";
}

TEST(ZooExploration, RoomWithFurniture) {
  expect_in_band(spacing_in("room:seed=2", zigzag(1.65, 1.45, 1.0)));
}

TEST(ZooExploration, OfficeOfRepeatedDesks) {
  expect_in_band(spacing_in("office:seed=1", zigzag(6.15, 4.65, 1.0)));
}

TEST(ZooExploration, FieldFromOneMetre) {
  const Spacing s = spacing_in("field:seed=1", zigzag(8.65, 8.95, 1.0));
  expect_in_band(s);
  EXPECT_FALSE(in_band(s.fixed_m)) << "the room's threshold spaces the field's places " << s.fixed_m
                                   << " m apart: the band says nothing";
}

TEST(ZooExploration, HouseOfThreeRooms) {
  expect_in_band(
      spacing_in("house:rooms=3,room_min_m=2.5,room_max_m=3.5,seed=1", zigzag(0.321, 0.446, 1.0)));
}

}  // namespace
}  // namespace omninav::memory
