#pragma once
// The parameters of a configuration folder's files, as the commands and `omninav evaluate` use
// them. Plain data: libs/config (config_folder.hpp) loads them from the YAML files.

#include <filesystem>

#include "omninav/compass/compass_config.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/evaluation/navigation_trials.hpp"
#include "omninav/lattice/confirmed_links.hpp"
#include "omninav/lattice/organise.hpp"
#include "omninav/memory/memory_config.hpp"
#include "omninav/navigation/navigator.hpp"
#include "omninav/navigation/place_belief.hpp"
#include "omninav/navigation/route_planner.hpp"
#include "omninav/omni/unwrap.hpp"
#include "omninav/sim/virtual_robot.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::evaluation {

// camera.yaml.
struct CameraConfig {
  PanoramaGeometry panorama;
  omni::UnwrapParams unwrap;
};

// navigation.yaml, with the confirmed links of lattice.yaml (the plan runs over the lattice's
// graph).
struct NavigationConfig {
  navigation::RouteParams route;
  navigation::LinkParams links;
  navigation::BeliefParams belief;
  navigation::NavigatorParams navigator;
  sim::RobotParams robot;
  TrialParams trials;
};

// Every file of a configuration folder.
struct ConfigFolder {
  std::filesystem::path dir;  // absolute: the commands that remake a figure name it
  CameraConfig camera;
  sim::WorldsConfig worlds;
  compass::CompassConfig compass;
  memory::MemoryConfig memory;
  lattice::OrganiseParams lattice;
  NavigationConfig navigation;
};

}  // namespace omninav::evaluation
