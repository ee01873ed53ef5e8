#pragma once
// The two kinds of constraint of the lattice, as Ceres residual functors (Ceres'
// examples/slam/pose_graph_2d style: the measurement as const members, a templated operator(),
// a static factory returning the AutoDiff cost function).

#include <ceres/autodiff_cost_function.h>

#include <cmath>

namespace omninav::lattice {

// A spring between two places (Menegatti et al. 2004, §3.2): its force is proportional to the
// difference between the places' distance on the lattice and the spring's rest length, the
// distance estimated from their similarity. Residual: √K · (|p_a − p_b| − rest_length).
class SpringResidual {
 public:
  // at_least: a one-sided spring (SpringMeasurement::at_least), zero once stretched past rest.
  SpringResidual(double rest_length_m, double stiffness, bool at_least = false)
      : rest_length_m_(rest_length_m), sqrt_stiffness_(std::sqrt(stiffness)), at_least_(at_least) {}

  template <typename T>
  bool operator()(const T* const a, const T* const b, T* residual) const {
    const T dx = a[0] - b[0];
    const T dy = a[1] - b[1];
    // The squared length is nudged off zero: the derivative of √ at 0 is infinite.
    const T length = ceres::sqrt(dx * dx + dy * dy + T(1e-12));
    const T stretch = length - T(rest_length_m_);
    residual[0] = at_least_ && stretch > T(0) ? T(0) : T(sqrt_stiffness_) * stretch;
    return true;
  }

  static ceres::CostFunction* Create(double rest_length_m, double stiffness,
                                     bool at_least = false) {
    return new ceres::AutoDiffCostFunction<SpringResidual, 1, 2, 2>(
        new SpringResidual(rest_length_m, stiffness, at_least));
  }

 private:
  const double rest_length_m_;
  const double sqrt_stiffness_;
  const bool at_least_;
};

// A motion between two places measured from the Fourier phases (Menegatti et al. 2004,
// §3.4: the direction) together with its length (the exploration's step, or the spring's
// length): a spring that also knows which way it points. Residuals, in standard deviations:
// along the measured direction u, (Δ·u − length) / σ_length; across it, (Δ·u⊥) / (σ_direction ·
// length), the small-angle sideways error. Both are linear in the positions, so that a lattice
// held by such motions has one minimum and cannot escape to infinity or collapse to a point,
// which an angle-only residual (atan2 of Δ) allows: it does not care how long Δ is.
class MotionResidual {
 public:
  MotionResidual(double direction_rad, double length_m, double direction_stddev_rad,
                 double length_stddev_m)
      : cos_(std::cos(direction_rad)),
        sin_(std::sin(direction_rad)),
        length_m_(length_m),
        along_weight_(1.0 / length_stddev_m),
        across_weight_(1.0 / (direction_stddev_rad * length_m)) {}

  template <typename T>
  bool operator()(const T* const from, const T* const to, T* residual) const {
    const T dx = to[0] - from[0];
    const T dy = to[1] - from[1];
    residual[0] = T(along_weight_) * (T(cos_) * dx + T(sin_) * dy - T(length_m_));
    residual[1] = T(across_weight_) * (T(cos_) * dy - T(sin_) * dx);
    return true;
  }

  static ceres::CostFunction* Create(double direction_rad, double length_m,
                                     double direction_stddev_rad, double length_stddev_m) {
    return new ceres::AutoDiffCostFunction<MotionResidual, 2, 2, 2>(
        new MotionResidual(direction_rad, length_m, direction_stddev_rad, length_stddev_m));
  }

 private:
  const double cos_;
  const double sin_;
  const double length_m_;
  const double along_weight_;
  const double across_weight_;
};

}  // namespace omninav::lattice
