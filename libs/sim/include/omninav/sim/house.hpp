#pragma once
// A house: rooms of different sizes and looks on both sides of a corridor, each joined to it
// by a doorway (and some to their neighbour). Every room and the corridor has its own paint,
// floor (tiles, planks or carpet), pictures and furniture, so that rooms can be told apart;
// walls are obstacles with gaps at the doorways, which are wide enough for the robot.
// Seeded and deterministic. World::regions names the rooms ("room 1".."room N", south row
// first, west to east) and the "corridor".

#include <cstdint>

#include "omninav/sim/world.hpp"

namespace omninav::sim {

struct HouseParams {
  int rooms = 5;                  // on both sides of the corridor, south row first
  double room_min_m = 3.0;        // room widths along the corridor are drawn in [min, max]
  double room_max_m = 5.0;        // and each row's depth too
  double corridor_width_m = 1.4;  // between the two rows of rooms
  double door_width_m = 1.0;      // clear width of every doorway
  double height_m = 2.6;          // floor to ceiling
  int furniture = 3;              // boxes per room, kept clear of doorways
  double texture_px_per_m = 100.0;
  int seed = 1;
};

// Reads a house's keys from worlds.yaml's `house:` section or from a spec (same keys).
template <typename Reader>
void read_house_keys(const Reader& reader, HouseParams& params) {
  reader.read("rooms", params.rooms, 2, 10);
  reader.read("room_min_m", params.room_min_m, 2.5, 8.0);
  reader.read("room_max_m", params.room_max_m, 2.5, 8.0);
  reader.read("corridor_width_m", params.corridor_width_m, 1.0, 3.0);
  reader.read("door_width_m", params.door_width_m, 0.8, 1.5);
  reader.read("height_m", params.height_m, 2.2, 4.0);
  reader.read("furniture", params.furniture, 0, 8);
  reader.read("texture_px_per_m", params.texture_px_per_m, 10.0, 400.0);
  reader.read("seed", params.seed, 0, 1'000'000'000);
}

// Throws UsageError when room_min_m exceeds room_max_m.
World make_house(const HouseParams& params);

}  // namespace omninav::sim
