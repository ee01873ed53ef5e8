#pragma once
// Loading the YAML files of the configuration folder, each whole and strictly: every section a
// file has is read by its component's loader, then unknown keys are errors.

#include <filesystem>

#include "omninav/compass/compass_config.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/lattice/organise.hpp"
#include "omninav/memory/memory_config.hpp"
#include "omninav/navigation/navigator.hpp"
#include "omninav/navigation/trials.hpp"
#include "omninav/omni/unwrap.hpp"
#include "omninav/sim/virtual_robot.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::cli {

struct CameraConfig {
  PanoramaGeometry panorama;
  omni::UnwrapParams unwrap;
};

// <config_dir>/camera.yaml: sections panorama and unwrap.
CameraConfig load_camera_config(const std::filesystem::path& config_dir);

// <config_dir>/worlds.yaml: sections room, house, field, office, obj and render; the render
// geometry is `panorama`.
sim::WorldsConfig load_worlds_config(const std::filesystem::path& config_dir,
                                     const PanoramaGeometry& panorama);

// The help of a --world option, the same in every command that renders.
inline constexpr const char* kWorldOptionHelp =
    "A world family, with optional keys overriding worlds.yaml: family[:key=value,...], "
    "or a Wavefront .obj file. Families:\n"
    "  room (size_x_m, size_y_m 3-12, height_m, boxes 0-20, walls plain|textured, seed)\n"
    "  house (rooms 2-10, room_min_m, room_max_m, corridor_width_m, door_width_m, height_m, "
    "furniture, seed): rooms of different looks joined by doorways and a corridor\n"
    "  field (size_m, tussocks, grass_min_m, grass_max_m, bushes, trees, rocks, "
    "horizon trees|hills|none, seed): grass tussocks, bushes, trees, hills and sky\n"
    "  office (rows, desks_per_row, desk_pitch_m, row_pitch_m, column_every, height_m, "
    "clutter 0-1, seed): identical desks at a regular pitch\n"
    "Example: room:seed=3,size_x_m=9,boxes=12,walls=plain (docs/worlds.md lists every key)";

// <config_dir>/compass.yaml: sections distance, minimiser, phase, subpixel, sampling,
// confidence and input (libs/compass/.../compass_config.hpp).
compass::CompassConfig load_compass_config(const std::filesystem::path& config_dir);

// <config_dir>/memory.yaml: sections signature, exploration and localisation
// (libs/memory/.../memory_config.hpp).
memory::MemoryConfig load_memory_config(const std::filesystem::path& config_dir);

// <config_dir>/lattice.yaml: section organise (libs/lattice/.../organise.hpp).
lattice::OrganiseParams load_lattice_config(const std::filesystem::path& config_dir);

struct NavigationConfig {
  navigation::RouteParams route;
  navigation::NavigatorParams navigator;
  sim::RobotParams robot;
  navigation::TrialParams trials;
};

// <config_dir>/navigation.yaml: sections route, navigator, robot and trials.
NavigationConfig load_navigation_config(const std::filesystem::path& config_dir);

}  // namespace omninav::cli
