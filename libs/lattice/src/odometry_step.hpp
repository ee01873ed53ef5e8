#pragma once
// The robot's step between two places as its odometry measured it.

#include <Eigen/Core>
#include <optional>

#include "omninav/memory/visual_memory.hpp"

namespace omninav::lattice {

struct OdometryStep {
  Eigen::Vector2d translation_m;  // b's position in a's frame (x forward, y left)
  double turn_rad = 0.0;          // heading(b) − heading(a)
};

// None unless both places kept the robot's odometry.
std::optional<OdometryStep> odometry_step(const memory::VisualMemory& memory, int a, int b);

}  // namespace omninav::lattice
