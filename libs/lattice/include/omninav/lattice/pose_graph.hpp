#pragma once
// The lattice of a map made by driving, as a robust 2-D pose graph solved by Ceres: each place
// a pose (x, y, heading), each confirmed link a measurement of the pose of one place in the
// frame of the other, and the springs of the appearance model as weak constraints beside them.
// The robot's own path (its odometry, or the spacing and the phases'
// direction of motion) holds the places of a stream together; a revisit pulls two stretches
// onto each other. A revisit is a claim from appearance and may be wrong, so it is
// switchable (Sünderhauf & Protzel 2012, "Switchable constraints for robust pose graph SLAM"):
// its residual is scaled by a switch s in [0, 1] that the solver optimises with the poses,
// against a prior (1 − s)/Ξ that keeps it on unless the rest of the graph disagrees.
// The gauge is fixed explicitly: the first place of each connected piece keeps its starting
// pose (place 0 at the origin, facing +x). The start: dead reckoning, then the headings from
// the turns alone and the positions with the headings held, revisits under a Cauchy loss
// (LAGO's order, Carlone et al. 2014). Sparse: one block per measurement, solved by sparse
// Cholesky; nothing is done for all pairs of places.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "omninav/lattice/spring_lattice.hpp"

namespace omninav::lattice {

// The pose of place `to` in the frame of place `from` (x forward along from's heading, y to
// its left), with its uncertainty.
struct RelativePoseMeasurement {
  int from = 0;
  int to = 0;
  Eigen::Vector2d translation_m = Eigen::Vector2d::Zero();
  double turn_rad = 0.0;  // heading(to) − heading(from)
  // Standard deviations of the translation along the measured direction and across it (equal
  // when the translation has no direction worth the name), and of the turn.
  double along_stddev_m = 0.1;
  double across_stddev_m = 0.1;
  double turn_stddev_rad = 0.1;
  bool switchable = false;  // a revisit: the solver may switch it off
};

struct PoseGraphParams {
  // Ξ of Sünderhauf & Protzel 2012: the standard deviation of a switch's prior (their
  // experiments' 1); a smaller one makes switching a revisit off dearer.
  double switch_prior_stddev = 1.0;
  int max_iterations = 100;
  int threads = 1;

  // Throws UsageError naming the key (core/param_check.hpp).
  void check() const;
};

struct PoseGraphResult {
  std::vector<Eigen::Vector3d> poses;  // x (m), y (m), heading (rad) of each place
  std::vector<double> switches;        // one per switchable measurement, in their order
  int pieces = 0;  // connected pieces of the places by the measurements kept (switch ≥ 0.5)
  bool converged = false;
  std::string summary;  // Ceres' one-line report
};

// Solves for `place_count` poses from `measurements` and, as weak constraints on the places'
// positions, `springs` (the distances estimated from similarity, Menegatti et al. 2004, §3.2:
// stiffness and Cauchy loss as the spring model's, spring_params; none: an empty list). Throws
// UsageError when a measurement names a place out of range or has a standard deviation that is
// not positive.
PoseGraphResult solve_pose_graph(int place_count,
                                 const std::vector<RelativePoseMeasurement>& measurements,
                                 const std::vector<SpringMeasurement>& springs,
                                 const LatticeParams& spring_params,
                                 const PoseGraphParams& params = {});

}  // namespace omninav::lattice
