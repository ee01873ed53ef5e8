// The route's match test (memory_places.hpp: an image matches a place only when its
// dissimilarity per value to its best place is at most route.match_dissimilarity_ratio times the
// map's median link) against ground truth in three families of the zoo: a 7 × 5 grid at 30 cm
// rendered in the world (the full suite's corners, its 360 × 45 panoramas) and explored as a
// grid database is; views rendered at random free poses and headings among the places must
// match; views of the other worlds must not, nor noise where the zoo says the ratio rejects it
// (config/navigation.yaml, docs/navigation.md: not in the office and the house).

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "omninav/io/frame.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "omninav/signature/signature.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/trajectory.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::navigation {
namespace {

constexpr double kSpacing_m = 0.3;
constexpr int kNx = 7, kNy = 5;

struct GridMap {
  memory::VisualMemory memory{memory::MapParameters{}};
  std::vector<cv::Mat> on_map_views;  // random free poses among the places
};

GridMap grid_map(const std::string& spec, double x0_m, double y0_m) {
  const sim::World world = sim::load_world(spec, sim::WorldsConfig{});
  sim::RenderParams render;
  render.geometry.width_px = 360;
  render.geometry.height_px = 45;
  const sim::Renderer renderer(world, render);
  GridMap map;
  memory::ExplorationParams exploration;
  exploration.thumbnail_width_px = 8;
  memory::Explorer explorer(map.memory, exploration, "grid", "zoo_match_test.cpp",
                            memory::FrameOrder::kUnordered);
  const sim::Trajectory grid = sim::make_trajectory(
      "grid:x0=" + std::to_string(x0_m) + ",y0=" + std::to_string(y0_m) +
          ",nx=" + std::to_string(kNx) + ",ny=" + std::to_string(kNy) + ",spacing_m=0.3,z_m=1",
      world);
  std::vector<Eigen::Vector2d> places;
  for (std::size_t i = 0; i < grid.poses.size(); ++i) {
    io::Frame frame;
    frame.index = static_cast<int>(i);
    frame.truth = grid.poses[i].pose;
    frame.image = renderer.render(*frame.truth);
    frame.source = spec + "#" + std::to_string(i);
    explorer.add_place(frame);
    places.push_back(frame.truth->floor_position());
  }
  std::mt19937 random(5);
  std::uniform_real_distribution<double> x(x0_m, x0_m + (kNx - 1) * kSpacing_m);
  std::uniform_real_distribution<double> y(y0_m, y0_m + (kNy - 1) * kSpacing_m);
  std::uniform_real_distribution<double> heading(-M_PI, M_PI);
  for (int drawn = 0; map.on_map_views.size() < 30 && drawn < 3000; ++drawn) {
    const CameraPose pose{x(random), y(random), 1.0, heading(random), 0.0, 0.0};
    if (!world.is_free(pose.x_m, pose.y_m, 0.05)) continue;
    double nearest_m = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector2d& p : places) {
      nearest_m = std::min(nearest_m, (p - pose.floor_position()).norm());
    }
    if (nearest_m > kSpacing_m * std::sqrt(0.5)) continue;  // off the grid, as evaluate
    map.on_map_views.push_back(renderer.render(pose));
  }
  return map;
}

// The share of `views` that match a place of `map` by the route's criterion.
double share_matched(const GridMap& map, const std::vector<cv::Mat>& views) {
  const memory::Localiser localiser(map.memory, memory::LocalisationParams{});
  signature::SignatureExtractor extractor(map.memory.parameters().signature);
  const double limit = match_limit(map.memory, RouteParams{});
  int matched = 0;
  for (const cv::Mat& view : views) {
    matched += !no_match_reason(localiser.localise(extractor.compute(view, "view")), limit);
  }
  return static_cast<double>(matched) / static_cast<double>(views.size());
}

std::vector<cv::Mat> noise_views() {
  std::vector<cv::Mat> views;
  for (int i = 0; i < 10; ++i) {
    cv::Mat noise(45, 360, CV_8UC3);
    cv::RNG(100 + i).fill(noise, cv::RNG::UNIFORM, 0, 256);
    views.push_back(noise);
  }
  return views;
}

TEST(ZooMatch, OnMapViewsMatchForeignViewsAndNoiseDoNot) {
  std::map<std::string, GridMap> maps;
  maps.emplace("field", grid_map("field:seed=1", 8.65, 8.95));
  maps.emplace("office", grid_map("office:seed=1", 6.15, 4.65));
  maps.emplace("room", grid_map("room:seed=1", 1.65, 1.45));
  for (const auto& [name, map] : maps) {
    ASSERT_EQ(map.on_map_views.size(), 30u) << name;
    const double on = share_matched(map, map.on_map_views);
    std::cout << name << ": " << on << " of views among its places matched;";
    // Over the zoo's rows >= 99% (config/navigation.yaml); one miss in 30 allowed.
    EXPECT_GE(on, 0.96) << name;
    for (const auto& [other, foreign] : maps) {
      if (other == name) continue;
      const double off = share_matched(map, foreign.on_map_views);
      std::cout << " " << other << "'s views " << off << ";";
      // Over the zoo's rows the field's and the built worlds' views never match each other's
      // maps; the office's and the room's do in part (3-13%), not in these two.
      EXPECT_EQ(off, 0.0) << other << " on " << name;
    }
    const double noise = share_matched(map, noise_views());
    std::cout << " noise " << noise << "\n";
    // Noise, whose rows hold every frequency a little, lies near the office's (and the house's)
    // plain views: it matches this office map (9 of 10; 0-15% over the zoo's office rows).
    if (name != "office") {
      EXPECT_EQ(noise, 0.0) << name;
    }
  }
}

}  // namespace
}  // namespace omninav::navigation
