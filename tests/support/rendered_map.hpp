#pragma once
// Visual memories explored from trajectories rendered in a world, headings from the truth (so
// that what is measured on them does not depend on the compass), as `omninav render
// --trajectory ...` then `omninav explore` with heading_source truth:
//   - rendered_grid_map: a grid sweep as a grid database lists it, every pose a place;
//   - rendered_run_map: a stream (a route, a zig-zag), a place every `every_m` metres travelled.
// explored_stream explores frames already rendered as a stream, with any heading source.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "omninav/io/frame.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/trajectory.hpp"

namespace omninav::testing {

// Each pose of the trajectory rendered, with the pose as the frame's truth (and the odometry
// beside it when the spec has odometry_noise).
inline std::vector<io::Frame> rendered_frames(const sim::World& world,
                                              const sim::RenderParams& render,
                                              const std::string& trajectory_spec,
                                              const std::string& source) {
  const sim::Renderer renderer(world, render);
  const sim::Trajectory trajectory = sim::make_trajectory(trajectory_spec, world);
  std::vector<io::Frame> frames(trajectory.poses.size());
  for (std::size_t i = 0; i < trajectory.poses.size(); ++i) {
    frames[i].index = static_cast<int>(i);
    frames[i].image = renderer.render(trajectory.poses[i].pose);
    frames[i].truth = trajectory.poses[i].pose;
    frames[i].odometry = trajectory.poses[i].odometry;  // when the spec asks for odometry
    frames[i].source = source + "#" + std::to_string(i);
  }
  return frames;
}

inline memory::VisualMemory rendered_grid_map(const sim::World& world,
                                              const sim::RenderParams& render,
                                              const std::string& grid_spec,
                                              const std::string& description) {
  memory::VisualMemory map{memory::MapParameters{}};
  memory::ExplorationParams exploration;
  exploration.heading_source = memory::HeadingPolicy::kTruth;
  memory::Explorer explorer(map, exploration, "grid", description, memory::FrameOrder::kUnordered);
  for (const io::Frame& frame : rendered_frames(world, render, grid_spec, "grid")) {
    explorer.add_place(frame);
  }
  return map;
}

// How a stream is explored: as `omninav explore --every-m every_m --dissimilarity 0` (with
// --odometry when `odometry`), the places' headings by `headings`.
struct StreamExploration {
  double every_m = 0.3;
  memory::HeadingPolicy headings = memory::HeadingPolicy::kTruth;
  bool odometry = false;
};

// The frames of one run (named `input`) explored into a new map.
inline memory::VisualMemory explored_stream(const std::vector<io::Frame>& frames,
                                            const StreamExploration& how, const std::string& input,
                                            const std::string& description) {
  memory::VisualMemory map{memory::MapParameters{}};
  memory::ExplorationParams exploration;
  exploration.heading_source = how.headings;
  exploration.new_place_dissimilarity = 0.0;
  exploration.every_m = how.every_m;
  exploration.odometry = how.odometry;
  memory::Explorer explorer(map, exploration, input, description, memory::FrameOrder::kStream);
  for (const io::Frame& frame : frames) explorer.add(frame);
  return map;
}

inline memory::VisualMemory rendered_run_map(const sim::World& world,
                                             const sim::RenderParams& render,
                                             const std::string& trajectory_spec, double every_m,
                                             const std::string& description) {
  return explored_stream(rendered_frames(world, render, trajectory_spec, "run"), {every_m}, "run",
                         description);
}

// The places' true positions as their lattice, in the lattice frame (origin at the first place,
// its heading along +x): for tests that isolate navigation from the spring model.
inline void set_truth_lattice(memory::VisualMemory& memory) {
  const CameraPose first = *memory.place(0).truth;
  std::vector<Eigen::Vector2d> lattice_positions;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    const CameraPose& truth = *memory.place(i).truth;
    lattice_positions.push_back(Eigen::Rotation2Dd(-first.heading_rad) *
                                (truth.floor_position() - first.floor_position()));
  }
  memory.set_lattice_positions(lattice_positions);
}

}  // namespace omninav::testing
