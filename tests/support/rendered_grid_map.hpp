#pragma once
// A visual memory explored from a grid trajectory rendered in a world: every grid pose a place,
// headings from the truth (so that what is measured on it does not depend on the compass), as
// `omninav render --trajectory grid:...` then `omninav explore` with heading_source truth.

#include <string>

#include "omninav/io/frame.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/trajectory.hpp"

namespace omninav::testing {

inline memory::VisualMemory rendered_grid_map(const sim::World& world,
                                              const sim::RenderParams& render,
                                              const std::string& grid_spec,
                                              const std::string& description) {
  const sim::Renderer renderer(world, render);
  memory::VisualMemory map{memory::MapParameters{}};
  memory::ExplorationParams exploration;
  exploration.heading_source = "truth";
  memory::Explorer explorer(map, exploration, "grid", description, memory::FrameOrder::kUnordered);
  const sim::Trajectory trajectory = sim::make_trajectory(grid_spec, world);
  for (std::size_t i = 0; i < trajectory.poses.size(); ++i) {
    io::Frame frame;
    frame.index = static_cast<int>(i);
    frame.image = renderer.render(trajectory.poses[i].pose);
    frame.truth = trajectory.poses[i].pose;
    frame.source = "grid#" + std::to_string(i);
    explorer.add_place(frame);
  }
  return map;
}

}  // namespace omninav::testing
