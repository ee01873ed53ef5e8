#pragma once
// Checks the trajectory tests share.

#include <string>
#include <vector>

#include "omninav/sim/trajectory.hpp"
#include "omninav/sim/world.hpp"

namespace omninav::sim::testing {

// Every pose of `route`, and every straight step between two, lies in the free space of `world`
// with `clearance_m` (a failure names `label` and the pose).
void expect_in_free_space(const World& world, const Trajectory& route, double clearance_m,
                          const std::string& label);

// make_trajectory(spec, world) throws an omninav::Error holding every fragment (a failure
// when it throws none).
void expect_trajectory_error(const std::string& spec, const World& world,
                             const std::vector<std::string>& fragments);

}  // namespace omninav::sim::testing
