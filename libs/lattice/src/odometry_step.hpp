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

// The standard deviations of a step's odometry, given its relative noise: wheel odometry's
// errors grow with the distance and the turn; a tenth of a spacing and of a radian keep a step
// on the spot from claiming certainty.
struct OdometryStepStddev {
  double translation_m = 0.0;  // along and across the step
  double turn_rad = 0.0;
};
OdometryStepStddev odometry_step_stddev(const OdometryStep& step, double noise, double spacing_m);

}  // namespace omninav::lattice
