#pragma once
// What the random routes in the free space (trajectory kinds wander and saccade) share: where
// such a route may start, which way ahead is clear of obstacles, and the body's heading
// oscillation about the direction of travel.

#include <cmath>
#include <opencv2/core.hpp>
#include <optional>

#include "omninav/sim/world.hpp"

namespace omninav::sim {

// The settings every route in the free space has (its spec's keys of the same names).
struct FreeRouteSettings {
  double x = 0.0, y = 0.0;   // start: the free point nearest the floor's centre by default
  double heading_rad = 0.0;  // initial direction of travel
  double speed_m_s = 0.2;
  double length_m = 0.0;    // the route's length, or
  double duration_s = 0.0;  // its duration (exactly one of them is positive)
  double wobble_rad = 0.0;  // the heading's oscillation about the travel: amplitude
  double wobble_period_s = 2.0;
  double clearance_m = 0.25;  // kept from obstacles and the floor's edge
  int seed = 1;
};

// The free point nearest (x, y), searched on rings 5 cm apart (x, y unchanged when none is).
void move_to_free_point(const World& world, double clearance_m, double& x, double& y);

// How far the walker looks ahead for obstacles: 0.5 s of travel, and at least two frames' steps.
double lookahead_m(double speed_m_s, double fps);

// The smallest turn from `direction` (rad, signed; 0 when it is clear), either way in steps of
// 10° up to 180°, after which the straight path `lookahead_m` ahead of (x, y) is free by
// `keep_m` (as a segment, so that no wall is too thin); nothing when no direction is free.
std::optional<double> turn_to_clear(const World& world, double x, double y, double lookahead_m,
                                    double keep_m, double direction);

// The body's heading about the direction of travel: a sinusoid whose amplitude and period are
// jittered by ±30 % each cycle (an animal scanning as it goes).
class Wobble {
 public:
  Wobble(double amplitude_rad, double period_s, cv::RNG& rng);

  double offset_rad() const { return amplitude_ * std::sin(phase_); }
  // One frame on.
  void advance(double fps, cv::RNG& rng);

 private:
  double mean_amplitude_rad_, mean_period_s_;
  double phase_, amplitude_, rate_;
};

}  // namespace omninav::sim
