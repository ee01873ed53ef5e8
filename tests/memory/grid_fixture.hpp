#pragma once
// The tests' ground truth: the built-in room, a 30 cm grid of places rendered at 360×45 (the
// paper's reference images were "taken on a 25 cm grid", Menegatti et al. 2004, §2.3, and "every 30
// cm", §3.3), and queries rendered at random poses between the grid points, at random headings.

#include <cmath>
#include <random>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/io/frame.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/room.hpp"
#include "omninav/sim/trajectory.hpp"

namespace omninav::memory::testing {

inline constexpr double kSpacing_m = 0.3;
inline constexpr const char* kGridSpec = "grid:nx=10,ny=8,spacing_m=0.3";

inline const sim::World& room() {
  static const sim::World world = sim::make_room({});
  return world;
}

inline const sim::Renderer& renderer() {
  static const sim::Renderer instance = [] {
    sim::RenderParams params;
    params.geometry.width_px = 360;
    params.geometry.height_px = 45;
    return sim::Renderer(room(), params);
  }();
  return instance;
}

inline io::Frame render_frame(const CameraPose& pose, int index, const std::string& source) {
  io::Frame frame;
  frame.index = index;
  frame.image = renderer().render(pose);
  frame.truth = pose;
  frame.source = source;
  return frame;
}

// The grid's frames, as `omninav render --trajectory grid:...` would write them.
inline const std::vector<io::Frame>& grid_frames() {
  static const std::vector<io::Frame> frames = [] {
    const sim::Trajectory grid = sim::make_trajectory(kGridSpec, room());
    std::vector<io::Frame> out;
    for (std::size_t i = 0; i < grid.poses.size(); ++i) {
      out.push_back(
          render_frame(grid.poses[i].pose, static_cast<int>(i), "grid#" + std::to_string(i)));
    }
    return out;
  }();
  return frames;
}

// A map of the grid: every grid image a place.
inline VisualMemory grid_memory(signature::ColourMode colour = signature::ColourMode::kLuminance) {
  MapParameters parameters;
  parameters.signature.colour = colour;
  VisualMemory memory(parameters);
  Explorer explorer(memory, {}, "grid", "grid_fixture.hpp", FrameOrder::kUnordered);
  for (const io::Frame& frame : grid_frames()) explorer.add_place(frame);
  return memory;
}

struct Query {
  io::Frame frame;
  std::size_t nearest_place = 0;  // by ground-truth distance
  double nearest_m = 0.0;
};

// `count` poses drawn uniformly inside the grid's cells (each within half a diagonal of a grid
// place, so that the nearest place is a real neighbour, not one left out for furniture), free
// of furniture by 0.15 m, at headings uniform over the circle. Seeded: the same every run.
inline std::vector<Query> random_queries(std::size_t count, unsigned seed = 5) {
  const std::vector<io::Frame>& grid = grid_frames();
  double min_x = 1e9, min_y = 1e9, max_x = -1e9, max_y = -1e9;
  for (const io::Frame& f : grid) {
    min_x = std::min(min_x, f.truth->x_m);
    max_x = std::max(max_x, f.truth->x_m);
    min_y = std::min(min_y, f.truth->y_m);
    max_y = std::max(max_y, f.truth->y_m);
  }
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> x(min_x, max_x), y(min_y, max_y), heading(-kPi, kPi);
  std::vector<Query> queries;
  while (queries.size() < count) {
    CameraPose pose{x(random), y(random), 1.0, heading(random), 0.0, 0.0};
    if (!room().is_free(pose.x_m, pose.y_m, 0.15)) continue;
    Query q;
    q.nearest_m = 1e9;
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const double d = std::hypot(grid[i].truth->x_m - pose.x_m, grid[i].truth->y_m - pose.y_m);
      if (d < q.nearest_m) {
        q.nearest_m = d;
        q.nearest_place = i;
      }
    }
    if (q.nearest_m > kSpacing_m * std::sqrt(0.5)) continue;
    q.frame = render_frame(pose, static_cast<int>(queries.size()),
                           "query#" + std::to_string(queries.size()));
    queries.push_back(std::move(q));
  }
  return queries;
}

}  // namespace omninav::memory::testing
