#pragma once
// Small worlds built for tests, whose panoramas can be predicted exactly.

#include "omninav/sim/world.hpp"

namespace omninav::sim::testing {

// A square hall, 2·half_m on a side, whose walls are black below `split_z_m` and white above,
// with a grey floor and ceiling: the black/white edge is a horizon at height split_z_m.
World horizon_hall(double half_m, double split_z_m, double height_m);

// Adds an axis-aligned box of flat colour `colour_bgr` centred at (x, y, z) with side `side_m`.
void add_coloured_box(World& world, cv::Vec3f centre, float side_m, cv::Vec3f colour_bgr);

}  // namespace omninav::sim::testing
