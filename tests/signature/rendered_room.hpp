#pragma once
// The built-in room and a renderer at the tests' small size (360×45, camera.yaml's default),
// made once per test program.

#include <memory>

#include "omninav/core/angles.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/room.hpp"

namespace omninav::signature::testing {

inline const sim::World& room() {
  static const sim::World world = sim::make_room({});
  return world;
}

inline const sim::Renderer& renderer(int width = 360, int height = 45) {
  static const sim::Renderer small = [] {
    sim::RenderParams params;
    params.geometry.width_px = 360;
    params.geometry.height_px = 45;
    return sim::Renderer(room(), params);
  }();
  if (width == 360 && height == 45) return small;
  static const sim::Renderer large = [] {
    sim::RenderParams params;
    params.geometry.width_px = 720;
    params.geometry.height_px = 80;
    return sim::Renderer(room(), params);
  }();
  return large;
}

inline cv::Mat render(double x_m, double y_m, double heading_deg, int width = 360,
                      int height = 45) {
  return renderer(width, height).render(CameraPose{x_m, y_m, 1.0, deg_to_rad(heading_deg), 0, 0});
}

}  // namespace omninav::signature::testing
