#pragma once
// Turns what a user names on the command line (`room` or a path to an .obj file) into a World,
// with the parameters of worlds.yaml.

#include <string>

#include "omninav/sim/renderer.hpp"
#include "omninav/sim/room.hpp"
#include "omninav/sim/world.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::sim {

struct WorldsConfig {
  RoomParams room;
  ObjWorldParams obj;
  RenderParams render;  // render.geometry comes from camera.yaml, not worlds.yaml
};

// Reads worlds.yaml (sections room, obj, render).
void load_worlds_config(const ConfigReader& config, WorldsConfig& worlds);

// `room` → the built-in room; anything else is a Wavefront OBJ file.
World load_world(const std::string& name_or_path, const WorldsConfig& worlds);

}  // namespace omninav::sim
