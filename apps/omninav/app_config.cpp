#include "app_config.hpp"

#include "omninav/core/config.hpp"

namespace omninav::cli {

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

}  // namespace omninav::cli
