#pragma once
// The spring-model lattice of Menegatti et al. 2004, §3.2-3.4 as one Ceres least-squares
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
  // The length is only a lower bound: the places are at least this far apart (a dissimilarity
  // on the plateau of Fig. 7 says "far", not how far). Such a spring pushes, never pulls.
  bool at_least = false;
};

// The motion from place `from` to place `to`: its direction in the lattice frame (the frame of
// the first place's heading: 0 along +x), measured from the phases (§3.4), and its length, with
// their standard deviations.
struct MotionMeasurement {
  int from = 0;
  int to = 0;
  double direction_rad = 0.0;
  double length_m = 0.0;
  double direction_stddev_rad = 0.15;  // §3.4: "uncertainty ... within 15%"
  double length_stddev_m = 0.1;
  // Between consecutive places of a stream: the robot went from one to the other, so the two
  // are surely near; the start is built on such steps (initial_positions).
  bool step = false;
};

struct LatticeParams {
  double correlation_range_m = 1.0;  // x₁ of Eq. 5: K(x₁) = 0.1
  double min_stiffness = 1e-3;       // springs weaker than this are dropped (sparsity)
  double loss_scale_m = 0.15;        // Cauchy loss on spring residuals: beyond ~this, a spring's
                                     // pull is discounted as an outlier (aliased places)
  double motion_loss_scale = 1.0;    // Cauchy loss on motion residuals, in standard deviations
  // Every spring's stiffness is multiplied by this (0..1): how much the dissimilarity says about
  // distance on this map (OrganiseParams::spring_weight).
  double spring_weight = 1.0;
  int max_iterations = 200;
  int threads = 1;
};

struct LatticeResult {
  std::vector<Eigen::Vector2d> positions;  // place i at positions[i]; place 0 at the origin
  std::size_t place_pairs = 0;    // n(n − 1)/2, the springs of §3.2's full model (Eq. 4)
  std::size_t springs_given = 0;  // offered: each place's most similar places
  std::size_t springs_kept = 0;   // after dropping negligible ones
  std::size_t motion_constraints = 0;
  bool converged = false;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  std::string summary;  // Ceres' one-paragraph report, for the log
};

// A spring's stiffness as a lattice uses it: Eq. 5 at params.correlation_range_m times
// params.spring_weight; 0 for a spring too weak to keep (K < min_stiffness) or from a place to
// itself.
double used_stiffness(const SpringMeasurement& spring, const LatticeParams& params);

// Arranges `place_count` places. Throws UsageError when a measurement names a place out of
// range or the places are not connected by springs and motions (the lattice would be
// undetermined).
LatticeResult solve_lattice(int place_count, const std::vector<SpringMeasurement>& springs,
                            const std::vector<MotionMeasurement>& motions,
                            const LatticeParams& params = {});

// Starting positions, when the motions reach every place: the plain (not robust) least-squares
// arrangement of the steps and of the other motions between places that the steps do not
// already join (along a stream: its steps alone, so that look-alike motions cannot bend the
// start; on a grid database, which has no steps: every motion, whose errors then average out).
// Otherwise classical multidimensional scaling of the shortest-path distances over the springs.
std::vector<Eigen::Vector2d> initial_positions(int place_count,
                                               const std::vector<SpringMeasurement>& springs,
                                               const std::vector<MotionMeasurement>& motions);

}  // namespace omninav::lattice
