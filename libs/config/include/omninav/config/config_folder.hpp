#pragma once
// Loading the YAML files of a configuration folder, each whole and strictly: every section a
// file has is read by its component's loader (each library has the loader of its own sections,
// e.g. memory::load_memory_config), then unknown keys are errors. The commands of apps/omninav,
// the ROS node and the Python module load their configuration here; `omninav evaluate` is given
// what it loads (evaluation/configuration.hpp).

#include <filesystem>

#include "omninav/compass/compass_config.hpp"
#include "omninav/evaluation/configuration.hpp"
#include "omninav/lattice/organise.hpp"
#include "omninav/memory/memory_config.hpp"
#include "omninav/navigation/live_session.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::config {

// <config_dir>/camera.yaml: sections panorama and unwrap.
evaluation::CameraConfig load_camera_config(const std::filesystem::path& config_dir);

// <config_dir>/worlds.yaml: sections room, house, field, office, obj and render; the render
// geometry is `panorama`.
sim::WorldsConfig load_worlds_config(const std::filesystem::path& config_dir,
                                     const PanoramaGeometry& panorama);

// <config_dir>/compass.yaml: sections distance, minimiser, phase, subpixel, sampling,
// confidence, uncertainty, min_warping and input (libs/compass/.../compass_config.hpp).
compass::CompassConfig load_compass_config(const std::filesystem::path& config_dir);

// <config_dir>/memory.yaml: sections signature, exploration and localisation
// (libs/memory/.../memory_config.hpp).
memory::MemoryConfig load_memory_config(const std::filesystem::path& config_dir);

// memory::use_compass_config with the compass of <config_dir>/compass.yaml, read only when the
// exploration takes its headings from the compass, as `explore` does.
void use_compass_config(const std::filesystem::path& config_dir,
                        memory::ExplorationParams& exploration);

// <config_dir>/lattice.yaml: sections links, driven and organise (libs/lattice/.../organise.hpp).
lattice::OrganiseParams load_lattice_config(const std::filesystem::path& config_dir);

// <config_dir>/navigation.yaml: sections route, belief, navigator, robot and trials; the links
// are lattice.yaml's.
evaluation::NavigationConfig load_navigation_config(const std::filesystem::path& config_dir);

// A live session's parameters (navigation/live_session.hpp): compass.yaml, memory.yaml (with
// use_compass_config, as `explore` does) and navigation.yaml's route, links, belief and navigator.
navigation::LiveSessionParams load_live_session_params(const std::filesystem::path& config_dir);

// Every file of the folder, for `omninav evaluate`.
evaluation::ConfigFolder load_config_folder(const std::filesystem::path& config_dir);

}  // namespace omninav::config
