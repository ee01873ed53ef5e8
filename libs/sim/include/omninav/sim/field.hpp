#pragma once
// A natural scene as insect-navigation research renders it (the "ant world" of Risse and
// Mangan; BoB robotics): flat textured ground with thousands of grass tussocks (clusters of
// thin tall blades, greens and browns), bushes and trees, a tree line and hills on the
// horizon, and a sky. Panoramas from 2 cm to 1.5 m above the ground are informative.
// Tree trunks, rocks and bushes are obstacles; grass is not (a robot pushes through it).
// Seeded and deterministic. The walkable area (World::floor) is the square
// [0, size_m] × [0, size_m]; tussocks also grow a few metres beyond it.

#include <string>
#include <string_view>

#include "omninav/sim/world.hpp"

namespace omninav::sim {

// What stands on the field's horizon.
enum class Horizon {
  kTrees,  // a tree line before hills
  kHills,
  kNone,
};

std::string to_string(Horizon horizon);
// "trees", "hills" or "none"; throws UsageError for any other text.
Horizon horizon_from_string(std::string_view text);

struct FieldParams {
  double size_m = 20.0;       // side of the square the robot may roam
  int tussocks = 6000;        // grass tussocks on that square (more in the margin round it)
  double grass_min_m = 0.05;  // tussock heights are drawn in [min, max]
  double grass_max_m = 0.4;
  int bushes = 12;  // obstacles, 0.3-0.9 m across
  int trees = 6;    // obstacles: a trunk and a crown above 2 m
  int rocks = 8;    // obstacles, low and flattened, 0.2-0.9 m across
  Horizon horizon = Horizon::kTrees;
  double texture_px_per_m = 40.0;  // ground texture resolution (at most 2048 px a side)
  int seed = 1;
};

// Reads a field's keys from worlds.yaml's `field:` section or from a spec (same keys).
template <typename Reader>
void read_field_keys(const Reader& reader, FieldParams& params) {
  reader.read("size_m", params.size_m, 5.0, 100.0);
  reader.read("tussocks", params.tussocks, 0, 50000);
  reader.read("grass_min_m", params.grass_min_m, 0.01, 1.0);
  reader.read("grass_max_m", params.grass_max_m, 0.01, 1.0);
  reader.read("bushes", params.bushes, 0, 200);
  reader.read("trees", params.trees, 0, 100);
  reader.read("rocks", params.rocks, 0, 200);
  std::string horizon = to_string(params.horizon);
  reader.read("horizon", horizon, {"trees", "hills", "none"});
  params.horizon = horizon_from_string(horizon);
  reader.read("texture_px_per_m", params.texture_px_per_m, 5.0, 200.0);
  reader.read("seed", params.seed, 0, 1'000'000'000);
}

// Throws UsageError when grass_min_m exceeds grass_max_m.
World make_field(const FieldParams& params);

}  // namespace omninav::sim
