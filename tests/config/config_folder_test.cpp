// Every YAML file shipped in config/ loads strictly (no unknown key, every value in range)
// through the loader the commands use; a file no loader reads is a failure, so that a new
// configuration file cannot ship untested.
#include "omninav/config/config_folder.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>

#include "support/shared_data.hpp"

namespace omninav::config {
namespace {

TEST(ShippedConfig, EveryFileLoadsStrictlyThroughItsLoader) {
  const std::filesystem::path dir = omninav::testing::config_dir();
  const PanoramaGeometry panorama = load_camera_config(dir).panorama;
  const std::map<std::string, std::function<void()>> loaders = {
      {"camera.yaml", [&] { load_camera_config(dir); }},
      {"worlds.yaml", [&] { load_worlds_config(dir, panorama); }},
      {"compass.yaml", [&] { load_compass_config(dir); }},
      {"memory.yaml", [&] { load_memory_config(dir); }},
      {"lattice.yaml", [&] { load_lattice_config(dir); }},
      {"navigation.yaml", [&] { load_navigation_config(dir); }},
  };
  std::set<std::string> loaded;
  for (const std::filesystem::directory_entry& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory()) continue;
    const auto loader = loaders.find(name);
    if (loader == loaders.end()) {
      ADD_FAILURE() << "config/" << name << " is shipped but no loader reads it";
      continue;
    }
    EXPECT_NO_THROW(loader->second()) << "config/" << name;
    loaded.insert(name);
  }
  EXPECT_EQ(loaded.size(), loaders.size()) << "a configuration file the commands need is missing";
}

}  // namespace
}  // namespace omninav::config
