#pragma once
// Loading the YAML files of the configuration folder, each whole and strictly: every section a
// file has is read by its component's loader, then unknown keys are errors.

#include <filesystem>

#include "omninav/core/panorama.hpp"
#include "omninav/omni/unwrap.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::cli {

struct CameraConfig {
  PanoramaGeometry panorama;
  omni::UnwrapParams unwrap;
};

// <config_dir>/camera.yaml: sections panorama and unwrap.
CameraConfig load_camera_config(const std::filesystem::path& config_dir);

// <config_dir>/worlds.yaml: sections room, obj and render; the render geometry is `panorama`.
sim::WorldsConfig load_worlds_config(const std::filesystem::path& config_dir,
                                     const PanoramaGeometry& panorama);

}  // namespace omninav::cli
