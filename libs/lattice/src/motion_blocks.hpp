#pragma once
// One place for turning motion measurements into Ceres residual blocks: the start's linear
// relaxation (initial_positions.cpp) and the robust problem (spring_lattice.cpp) add the same.

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <vector>

#include "omninav/lattice/residuals.hpp"
#include "omninav/lattice/spring_lattice.hpp"

namespace omninav::lattice::detail {

// One MotionResidual per motion over `positions` (which must outlive `problem`), all sharing
// `loss` (nullptr: plain least squares).
inline void add_motion_blocks(ceres::Problem& problem,
                              const std::vector<MotionMeasurement>& motions,
                              std::vector<Eigen::Vector2d>& positions, ceres::LossFunction* loss) {
  for (const MotionMeasurement& motion : motions) {
    ceres::CostFunction* cost = MotionResidual::Create(
        motion.direction_rad, motion.length_m, motion.direction_stddev_rad, motion.length_stddev_m);
    problem.AddResidualBlock(cost, loss, positions[motion.from].data(),
                             positions[motion.to].data());
  }
}

}  // namespace omninav::lattice::detail
