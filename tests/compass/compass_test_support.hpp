#pragma once
// Inputs for the compass tests: panoramas rendered in the built-in room (exact ground truth),
// random images, and the real ftl-arena panoramas of ../shared/data (skipped when absent).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>
#include <vector>

#include "omninav/compass/frame.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/pose.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/room.hpp"
#include "support/shared_data.hpp"

namespace omninav::compass::testing {

// The default room (seed 1) of worlds.yaml, built once for all tests.
inline const sim::World& room() {
  static const sim::World world = sim::make_room({});
  return world;
}

inline sim::RenderParams render_params(int width_px, int height_px, int rays_per_pixel = 3) {
  sim::RenderParams params;
  params.geometry.width_px = width_px;
  params.geometry.height_px = height_px;
  params.rays_per_pixel = rays_per_pixel;
  return params;
}

// A renderer of the default room at the given size, kept for the whole test program.
inline const sim::Renderer& room_renderer(int width_px, int height_px) {
  static std::vector<std::pair<std::pair<int, int>, std::unique_ptr<sim::Renderer>>> renderers;
  for (const auto& [size, renderer] : renderers) {
    if (size == std::make_pair(width_px, height_px)) return *renderer;
  }
  renderers.emplace_back(
      std::make_pair(width_px, height_px),
      std::make_unique<sim::Renderer>(room(), render_params(width_px, height_px)));
  return *renderers.back().second;
}

inline cv::Mat render_room(double x_m, double y_m, double heading_deg, int width_px = 360,
                           int height_px = 45) {
  return room_renderer(width_px, height_px)
      .render(CameraPose{x_m, y_m, 1.0, deg_to_rad(heading_deg), 0.0, 0.0});
}

// Uniform random 8-bit pixels, seeded.
inline cv::Mat random_image(int width, int height, int channels, std::uint32_t seed) {
  cv::Mat image(height, width, CV_8UC(channels));
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> value(0, 255);
  for (int r = 0; r < height; ++r) {
    std::uint8_t* row = image.ptr<std::uint8_t>(r);
    for (int i = 0; i < width * channels; ++i) row[i] = static_cast<std::uint8_t>(value(random));
  }
  return image;
}

inline std::filesystem::path ftl_route_dir() {
  return omninav::testing::shared_data_dir() / "real/ftl-arena/route";
}

// snapshot_<index>.png of the real route (call OMNINAV_REQUIRE_SHARED_DATA first).
inline cv::Mat ftl_route_image(int index) {
  const std::filesystem::path file =
      ftl_route_dir() / ("snapshot_" + std::to_string(index) + ".png");
  cv::Mat image = cv::imread(file.string(), cv::IMREAD_COLOR);
  if (image.empty()) throw std::runtime_error("cannot read " + file.string());
  return image;
}

}  // namespace omninav::compass::testing
