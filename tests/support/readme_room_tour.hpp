#pragma once
// The README's walkthrough as a map: a tour of the built-in room (lanes 30 cm apart) rendered at
// the full suite's 360 x 45, with 5 % wheel odometry, explored into a place every 30 cm the
// odometry says the robot drove (or, without it, the truth says), headings from the compass.
// Not organised. The frames are rendered once per test program.

#include <vector>

#include "omninav/memory/exploration.hpp"
#include "omninav/sim/world_loader.hpp"
#include "support/rendered_map.hpp"

namespace omninav::testing {

inline constexpr double kReadmeTourSpacing_m = 0.3;

inline memory::VisualMemory readme_room_tour(bool odometry) {
  static const std::vector<io::Frame> frames = [] {
    sim::RenderParams render;
    render.geometry.width_px = 360;
    render.geometry.height_px = 45;
    return rendered_frames(sim::load_world("room", sim::WorldsConfig{}), render,
                           "tour:x0=1.5,y0=1.5,x1=4.5,y1=3.5,fps=2,odometry_noise=0.05", "tour");
  }();
  return explored_stream(frames, {kReadmeTourSpacing_m, memory::HeadingPolicy::kCompass, odometry},
                         "tour", "readme_room_tour.hpp");
}

}  // namespace omninav::testing
