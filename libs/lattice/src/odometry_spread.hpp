#pragma once
// How far the odometry may have drifted between two places of a stream: the standard deviation
// of dead reckoning from one to the other, propagated to first order from each step's errors
// (odometry_step_stddev). A step's error in length moves the later place by that much; an error
// in a step's turn swings everything after it round that step's end, so the later place moves
// by the turn's error times its distance from there (Kelly 2004, "Linearized error propagation
// in odometry"). With prefix sums over each stream the spread between any two of its places
// costs a few operations, whatever their distance along it.

#include <Eigen/Core>
#include <vector>

#include "omninav/memory/visual_memory.hpp"

namespace omninav::lattice {

class OdometrySpread {
 public:
  // `streams`: chains of consecutive places (each in order); `noise`: the odometry's relative
  // standard deviation of a step's distance and turn.
  OdometrySpread(const memory::VisualMemory& memory, const std::vector<std::vector<int>>& streams,
                 double noise, double spacing_m);

  // The standard deviation (metres, the root of the covariance's trace) of place `to`'s
  // position seen from place `from` by dead reckoning, both of stream `stream` at these
  // positions; infinite when a step between them has no odometry.
  double stddev_m(int stream, int from, int to) const;

 private:
  // Per stream, per position k: sums over its steps up to k (the step into place k).
  struct Sums {
    double length_variance = 0.0;       // Σ σ_length²
    double turn_variance = 0.0;         // Σ σ_turn²
    Eigen::Vector2d turn_moment{0, 0};  // Σ σ_turn² p
    double turn_second_moment = 0.0;    // Σ σ_turn² |p|²
    int unmeasured = 0;                 // steps without odometry
  };
  std::vector<std::vector<Sums>> sums_;
  std::vector<std::vector<Eigen::Vector2d>> positions_;  // the odometry's, (0, 0) where none
};

}  // namespace omninav::lattice
