#pragma once
// The configuration folder's loaders live in libs/evaluation (config_folder.hpp), because
// `omninav evaluate` loads the same files as the commands; the commands name them unqualified.

#include "omninav/evaluation/config_folder.hpp"

namespace omninav::cli {

using evaluation::CameraConfig;
using evaluation::load_camera_config;
using evaluation::load_compass_config;
using evaluation::load_lattice_config;
using evaluation::load_memory_config;
using evaluation::load_navigation_config;
using evaluation::load_worlds_config;
using evaluation::NavigationConfig;
using evaluation::use_compass_config;

}  // namespace omninav::cli
