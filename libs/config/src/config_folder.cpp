#include "omninav/config/config_folder.hpp"

#include "omninav/core/config.hpp"

namespace omninav::config {

namespace fs = std::filesystem;

using evaluation::CameraConfig;
using evaluation::NavigationConfig;

CameraConfig load_camera_config(const std::filesystem::path& config_dir) {
  const ConfigReader config = ConfigReader::from_file(config_dir / "camera.yaml");
  CameraConfig camera;
  load_panorama_geometry(config.section("panorama"), camera.panorama);
  camera.unwrap = omni::unwrap_params_for(camera.panorama);
  omni::load_unwrap_params(config.section("unwrap"), camera.unwrap);
  config.require_all_known();
  return camera;
}

sim::WorldsConfig load_worlds_config(const std::filesystem::path& config_dir,
                                     const PanoramaGeometry& panorama) {
  const ConfigReader config = ConfigReader::from_file(config_dir / "worlds.yaml");
  sim::WorldsConfig worlds;
  sim::load_worlds_config(config, worlds);
  config.require_all_known();
  worlds.render.geometry = panorama;
  return worlds;
}

compass::CompassConfig load_compass_config(const std::filesystem::path& config_dir) {
  const ConfigReader config = ConfigReader::from_file(config_dir / "compass.yaml");
  compass::CompassConfig compass;
  compass::load_compass_config(config, compass);
  config.require_all_known();
  // The joint rotation's scale planes need the rows' elevations.
  if (fs::exists(config_dir / "camera.yaml")) {
    compass.compass.joint.geometry = load_camera_config(config_dir).panorama;
  }
  return compass;
}

memory::MemoryConfig load_memory_config(const std::filesystem::path& config_dir) {
  return memory::load_memory_config(ConfigReader::from_file(config_dir / "memory.yaml"));
}

void use_compass_config(const std::filesystem::path& config_dir,
                        memory::ExplorationParams& exploration) {
  if (exploration.heading_source != memory::HeadingPolicy::kCompass &&
      exploration.heading_source != memory::HeadingPolicy::kAuto) {
    return;  // a compass.yaml that would not be used is not read
  }
  memory::use_compass_config(load_compass_config(config_dir), exploration);
}

lattice::OrganiseParams load_lattice_config(const std::filesystem::path& config_dir) {
  const ConfigReader config = ConfigReader::from_file(config_dir / "lattice.yaml");
  lattice::OrganiseParams params;
  // The organise section last: its loader checks the whole (OrganiseParams::check).
  lattice::load_link_params(config.section("links"), params.links);
  lattice::load_driven_params(config.section("driven"), params.driven);
  lattice::load_organise_params(config.section("organise"), params);
  config.require_all_known();
  return params;
}

NavigationConfig load_navigation_config(const std::filesystem::path& config_dir) {
  const ConfigReader config = ConfigReader::from_file(config_dir / "navigation.yaml");
  NavigationConfig navigation;
  navigation::load_route_params(config.section("route"), navigation.route);
  // The confirmed links are the lattice's (lattice.yaml): the plan runs over the same graph.
  navigation.links = load_lattice_config(config_dir).links;
  navigation::load_belief_params(config.section("belief"), navigation.belief);
  navigation::load_navigator_params(config.section("navigator"), navigation.navigator);
  sim::load_robot_params(config.section("robot"), navigation.robot);
  evaluation::load_trial_params(config.section("trials"), navigation.trials);
  config.require_all_known();
  return navigation;
}

navigation::LiveSessionParams load_live_session_params(const std::filesystem::path& config_dir) {
  navigation::LiveSessionParams params;
  const compass::CompassConfig compass = load_compass_config(config_dir);
  params.compass = compass.compass;
  params.compass_width_px = compass.width_px;
  params.memory = load_memory_config(config_dir);
  use_compass_config(config_dir, params.memory.exploration);
  const NavigationConfig navigation = load_navigation_config(config_dir);
  params.route = navigation.route;
  params.navigator = navigation.navigator;
  params.links = navigation.links;
  params.belief = navigation.belief;
  params.steering = {compass.min_warping, load_camera_config(config_dir).panorama};
  return params;
}

evaluation::ConfigFolder load_config_folder(const std::filesystem::path& config_dir) {
  evaluation::ConfigFolder config;
  config.dir = std::filesystem::absolute(config_dir).lexically_normal();
  config.camera = load_camera_config(config_dir);
  config.worlds = load_worlds_config(config_dir, config.camera.panorama);
  config.compass = load_compass_config(config_dir);
  config.memory = load_memory_config(config_dir);
  config.lattice = load_lattice_config(config_dir);
  config.navigation = load_navigation_config(config_dir);
  return config;
}

}  // namespace omninav::config
