#include "omninav/sim/world_loader.hpp"

#include "omninav/core/config.hpp"

namespace omninav::sim {

void load_worlds_config(const ConfigReader& config, WorldsConfig& worlds) {
  load_room_params(config.section("room"), worlds.room);
  const ConfigReader obj = config.section("obj");
  obj.read("y_up", worlds.obj.y_up);
  obj.read("scale_to_m", worlds.obj.scale_to_m, 1e-6, 1e6);
  load_render_params(config.section("render"), worlds.render);
}

World load_world(const std::string& name_or_path, const WorldsConfig& worlds) {
  if (name_or_path == "room") return make_room(worlds.room);
  return load_obj_world(name_or_path, worlds.obj);
}

}  // namespace omninav::sim
