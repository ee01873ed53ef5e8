#pragma once
// The spring-model lattice of 001_5bb151a4e28490b4.txt §3.2-3.4 as one Ceres least-squares
// problem: places are 2-D points; springs between pairs pull them to the distances estimated
// from their similarity, stiff when short and nearly slack when long (Eq. 5); the directions of
// motion between consecutive places (§3.4) keep periodic places from folding the lattice.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace omninav::lattice {

// A distance between two places estimated from their similarity.
struct SpringMeasurement {
  int a = 0;
  int b = 0;
  double length_m = 0.0;
};

// The direction of motion from place `from` to place `to`, in the lattice frame (the frame of
// the first place's heading: 0 along +x), with its standard deviation.
struct MotionMeasurement {
  int from = 0;
  int to = 0;
  double direction_rad = 0.0;
  double stddev_rad = 0.15;  // §3.4: "uncertainty concerning the motion direction is within 15%"
};

struct LatticeParams {
  double correlation_range_m = 1.0;  // x₁ of Eq. 5: K(x₁) = 0.1
  double min_stiffness = 1e-3;       // springs weaker than this are dropped (sparsity)
  double loss_scale_m = 0.15;        // Cauchy loss on spring residuals: beyond ~this, a spring's
                                     // pull is discounted as an outlier (aliased places)
  int max_iterations = 200;
  int threads = 1;
};

struct LatticeResult {
  std::vector<Eigen::Vector2d> positions;  // place i at positions[i]; place 0 at the origin
  std::size_t springs_given = 0;
  std::size_t springs_kept = 0;  // after dropping negligible ones
  std::size_t motion_constraints = 0;
  bool converged = false;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  std::string summary;  // Ceres' one-paragraph report, for the log
};

// Arranges `place_count` places. Throws UsageError when a measurement names a place out of
// range or the places are not connected by springs and motions (the lattice would be
// undetermined).
LatticeResult solve_lattice(int place_count, const std::vector<SpringMeasurement>& springs,
                            const std::vector<MotionMeasurement>& motions,
                            const LatticeParams& params = {});

// Starting positions: dead reckoning along the motion chain when every place after the first is
// reached by a motion measurement (step lengths from the springs between consecutive places),
// otherwise classical multidimensional scaling of the shortest-path distances over the springs.
std::vector<Eigen::Vector2d> initial_positions(int place_count,
                                               const std::vector<SpringMeasurement>& springs,
                                               const std::vector<MotionMeasurement>& motions);

}  // namespace omninav::lattice
