#pragma once
// A saccadic route (trajectory kind `saccade`): the motion of a walking insect or a small robot
// that the smooth `wander` lacks. Straight stretches at speed_m_s, each lasting an exponentially
// distributed time of mean stretch_s, the heading oscillating about the straight path (the
// route's wobble: an animal scanning as it walks); each ends in a saccade, a sharp turn on the
// spot of saccade_min_deg..saccade_max_deg either way at saccade_rate_deg_s (hundreds of degrees
// a second: a turn spans a few frames, as the saccades of flies and walking insects do), or,
// with probability stop_share, in a stop: the walker stands still for 0.5-1.5 stop_s (frames still
// coming) and then turns on the spot towards a direction uniform over the circle at
// spot_turn_rate_deg_s, as a robot turns in place. The walker keeps clearance_m from obstacles
// and the floor's edge as `wander` does (free_space.hpp): a stretch ends early where the path
// 0.5 s ahead is not clear, and a turn goes on past its drawn angle, in steps of 10°, to the
// nearest direction that is.

#include <string>
#include <vector>

#include "free_space.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/sim/trajectory.hpp"
#include "omninav/sim/world.hpp"

namespace omninav::sim {

struct SaccadeParams {
  double stretch_s = 2.0;                          // mean duration of a straight stretch
  double saccade_min_rad = deg_to_rad(30.0);       // the least saccade, either way
  double saccade_max_rad = deg_to_rad(120.0);      // the largest
  double saccade_rate_rad_s = deg_to_rad(500.0);   // a saccade's turn rate
  double stop_share = 0.25;                        // share of stretches that end in a stop
  double stop_s = 1.0;                             // mean duration of a stop (0.5-1.5 times)
  double spot_turn_rate_rad_s = deg_to_rad(60.0);  // the turn on the spot after a stop

  // Throws UsageError naming the key (as the spec spells it) and its valid range.
  void check() const;
};

// The poses of the route at `fps`, `max_poses` at most. Throws UsageError (without the spec,
// which the caller adds) for parameters out of range, a route of more than max_poses poses, and
// a walker boxed in (no direction clear by clearance_m).
std::vector<TimedPose> saccade_route(const World& world, const FreeRouteSettings& route,
                                     const SaccadeParams& params, double fps,
                                     std::size_t max_poses);

}  // namespace omninav::sim
