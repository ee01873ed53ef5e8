#pragma once
// A measured turn between two unknown headings as a least-squares residual, for Ceres'
// automatic differentiation (ceres::AutoDiffCostFunction<TurnResidual, 1, 1, 1>): the lattice's
// heading synchronisation and the pose graph's first start both solve headings from turns.
// Kept free of Ceres' headers: floor is found by argument-dependent lookup (ceres::floor for
// its Jets, std::floor for doubles).

#include <cmath>

#include "omninav/core/angles.hpp"

namespace omninav {

// An angle into [−π, π), for doubles and for Ceres' Jets alike (the Jets' floor is Ceres').
template <typename T>
T wrapped_angle(const T& angle) {
  using std::floor;
  const T two_pi(kTwoPi);
  return angle - two_pi * floor((angle + T(kPi)) / two_pi);
}

// wrap(θ_to − θ_from − turn) to [−π, π), in standard deviations (as Ceres'
// examples/slam/pose_graph_2d NormalizeAngle).
class TurnResidual {
 public:
  TurnResidual(double turn_rad, double stddev_rad)
      : turn_rad_(turn_rad), weight_(1.0 / stddev_rad) {}

  template <typename T>
  bool operator()(const T* const from, const T* const to, T* residual) const {
    residual[0] = T(weight_) * wrapped_angle(to[0] - from[0] - T(turn_rad_));
    return true;
  }

 private:
  const double turn_rad_;
  const double weight_;
};

}  // namespace omninav
