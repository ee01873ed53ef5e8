#pragma once
// The two kinds of constraint of the lattice, as Ceres residual functors (Ceres'
// examples/slam/pose_graph_2d style: the measurement as const members, a templated operator(),
// a static factory returning the AutoDiff cost function).

#include <ceres/autodiff_cost_function.h>

#include <cmath>

namespace omninav::lattice {

// A spring between two places (001_5bb151a4e28490b4.txt §3.2): its force is proportional to the
// difference between the places' distance on the lattice and the spring's rest length, the
// distance estimated from their similarity. Residual: √K · (|p_a − p_b| − rest_length).
class SpringResidual {
 public:
  SpringResidual(double rest_length_m, double stiffness)
      : rest_length_m_(rest_length_m), sqrt_stiffness_(std::sqrt(stiffness)) {}

  template <typename T>
  bool operator()(const T* const a, const T* const b, T* residual) const {
    const T dx = a[0] - b[0];
    const T dy = a[1] - b[1];
    // The squared length is nudged off zero: the derivative of √ at 0 is infinite.
    const T length = ceres::sqrt(dx * dx + dy * dy + T(1e-12));
    residual[0] = T(sqrt_stiffness_) * (length - T(rest_length_m_));
    return true;
  }

  static ceres::CostFunction* Create(double rest_length_m, double stiffness) {
    return new ceres::AutoDiffCostFunction<SpringResidual, 1, 2, 2>(
        new SpringResidual(rest_length_m, stiffness));
  }

 private:
  const double rest_length_m_;
  const double sqrt_stiffness_;
};

// The direction of motion from one place to the next, measured from the Fourier phase
// (001_5bb151a4e28490b4.txt §3.4), in the lattice frame. Residual: the angle between the
// lattice's step p_to − p_from and the measured direction, wrapped to (−π, π] inside the
// residual, times a weight (1 / the direction's standard deviation).
class MotionDirectionResidual {
 public:
  MotionDirectionResidual(double direction_rad, double weight)
      : direction_rad_(direction_rad), weight_(weight) {}

  template <typename T>
  bool operator()(const T* const from, const T* const to, T* residual) const {
    const T dx = to[0] - from[0];
    const T dy = to[1] - from[1];
    // Rotate the step by −direction: its angle is then the error, taken by atan2 in (−π, π].
    const T c = T(std::cos(direction_rad_)), s = T(std::sin(direction_rad_));
    const T along = c * dx + s * dy;
    const T across = -s * dx + c * dy;
    residual[0] = T(weight_) * ceres::atan2(across, along);
    return true;
  }

  static ceres::CostFunction* Create(double direction_rad, double weight) {
    return new ceres::AutoDiffCostFunction<MotionDirectionResidual, 1, 2, 2>(
        new MotionDirectionResidual(direction_rad, weight));
  }

 private:
  const double direction_rad_;
  const double weight_;
};

}  // namespace omninav::lattice
