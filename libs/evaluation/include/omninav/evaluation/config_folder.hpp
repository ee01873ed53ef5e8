#pragma once
// Loading the YAML files of the configuration folder, each whole and strictly: every section a
// file has is read by its component's loader, then unknown keys are errors. Shared by the
// commands of apps/omninav and by `omninav evaluate`, which runs what they run.

#include <filesystem>

#include "omninav/compass/compass_config.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/evaluation/navigation_trials.hpp"
#include "omninav/lattice/organise.hpp"
#include "omninav/memory/memory_config.hpp"
#include "omninav/lattice/confirmed_links.hpp"
#include "omninav/navigation/live_session.hpp"
#include "omninav/navigation/navigator.hpp"
#include "omninav/navigation/place_belief.hpp"
#include "omninav/omni/unwrap.hpp"
#include "omninav/sim/virtual_robot.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::evaluation {

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

// <config_dir>/compass.yaml: sections distance, minimiser, phase, subpixel, sampling,
// confidence, uncertainty, min_warping and input (libs/compass/.../compass_config.hpp).
compass::CompassConfig load_compass_config(const std::filesystem::path& config_dir);

// <config_dir>/memory.yaml: sections signature, exploration and localisation
// (libs/memory/.../memory_config.hpp).
memory::MemoryConfig load_memory_config(const std::filesystem::path& config_dir);

// When `exploration` takes its headings from the visual compass (heading_source compass or
// auto), the compass of <config_dir>/compass.yaml and its input width, as `explore` uses them.
void use_compass_config(const std::filesystem::path& config_dir,
                        memory::ExplorationParams& exploration);

// <config_dir>/lattice.yaml: section organise (libs/lattice/.../organise.hpp).
lattice::OrganiseParams load_lattice_config(const std::filesystem::path& config_dir);

struct NavigationConfig {
  navigation::RouteParams route;
  navigation::LinkParams links;
  navigation::BeliefParams belief;
  navigation::NavigatorParams navigator;
  sim::RobotParams robot;
  TrialParams trials;
};

// <config_dir>/navigation.yaml: sections route, links, belief, navigator, robot and trials.
NavigationConfig load_navigation_config(const std::filesystem::path& config_dir);

// A live session's parameters (navigation/live_session.hpp): compass.yaml, memory.yaml (with
// use_compass_config, as `explore` does) and navigation.yaml's route, links, belief and navigator.
navigation::LiveSessionParams load_live_session_params(const std::filesystem::path& config_dir);

}  // namespace omninav::evaluation
