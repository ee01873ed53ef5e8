#pragma once
// The built-in world: a rectangular room with textured walls, floor and ceiling and a number
// of furniture boxes of random size, colour and texture. Seeded and deterministic: the same
// parameters give the same room, texel for texel. The textures mix scales (posters, doors,
// windows, stripes, tiles, rugs, noise) so that places 30 cm apart look different.

#include <cstdint>

#include "omninav/sim/world.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::sim {

struct RoomParams {
  double size_x_m = 6.0;    // inside length along x
  double size_y_m = 5.0;    // inside length along y
  double height_m = 2.6;    // floor to ceiling
  int furniture_count = 8;  // boxes placed at random, not overlapping
  double furniture_min_side_m = 0.3;
  double furniture_max_side_m = 1.2;
  double furniture_min_height_m = 0.3;
  double furniture_max_height_m = 1.8;
  double furniture_gap_m = 0.5;     // free space kept between boxes and from the walls
  bool plain_walls = false;         // plain paint instead of pictures, doors and windows
  double texture_px_per_m = 100.0;  // resolution of the generated textures
  std::uint32_t seed = 1;           // same seed, same room
};

// Reads the `room:` section of worlds.yaml.
void load_room_params(const ConfigReader& section, RoomParams& params);

World make_room(const RoomParams& params);

}  // namespace omninav::sim
