#pragma once
// Camera trajectories for the renderer, with a frame rate and speed so that time and distance
// travelled are known. A trajectory is given as a spec string, `kind:key=value,key=value`:
//
//   rotate  on the spot:    x, y, heading_deg, turns (1), rate_deg_s (30; negative = clockwise)
//   line    straight:       x0, y0, x1, y1, speed_m_s (0.2); heading along the line
//   circle  round a centre: cx, cy, radius_m (1), turns (1), speed_m_s (0.2); heading tangent,
//                           counter-clockwise (negative speed: clockwise)
//   walk    random walk:    x, y, heading_deg, steps (200), step_m (0.05), turn_deg (20), seed (1);
//                           turns away from walls and furniture
//   wander  animal-like:    x, y (default: the free point nearest the centre), heading_deg,
//   length_m (10) or duration_s, speed_m_s (0.2),
//                           turn_rate_deg_s (30: mean of the exponentially distributed turn
//                           rates, changed every 0.5-3 s), wobble_deg (15) and wobble_period_s
//                           (2: heading oscillation about the direction of travel),
//                           clearance_m (0.25), seed (1); steers clear of obstacles
//   saccade insect-like:    x, y, heading_deg, length_m (10: distance travelled) or duration_s,
//                           speed_m_s (0.2), clearance_m (0.25), seed (1) as wander; straight
//                           stretches of exponential duration, mean stretch_s (2), the heading
//                           scanning about them (wobble_deg 10, wobble_period_s 1), each ended
//                           by a saccade on the spot of saccade_min_deg..saccade_max_deg (30..120)
//                           either way at saccade_rate_deg_s (500), or with probability
//                           stop_share (0.25) by a stop of 0.5-1.5 stop_s (1) and a turn on the
//                           spot to a random direction at spot_turn_rate_deg_s (60); steers clear
//                           of obstacles as wander (saccade.hpp in src/)
//   grid    grid sweep:     x0, y0, nx (10), ny (8), spacing_m (0.3), heading_deg (0); points
//                           inside furniture are left out (their grid index is skipped)
//   zigzag  boustrophedon:  x0, y0, x1, y1, rows (4), speed_m_s (0.2): rows from y0 to y1, each
//                           from x0 to x1 and back, joined at the ends
//           line and zigzag also take turn_rate_deg_s (90): at a corner the robot turns on the
//                           spot at this rate, frames still coming (0: turns between two frames)
//   tour    coverage:       x0, y0, x1, y1 (the rectangle toured, default the floor), lane_m
//                           (0.3), clearance_m (0.25), speed_m_s (0.2), turn_rate_deg_s (45),
//                           x, y (start: default a seeded random point), seed (1): a robot's
//                           coverage tour of the free space, every room through its doorways,
//                           in lanes lane_m apart (tour.hpp)
//   csv     from a file:    path; columns x_m, y_m, heading_deg (required), time_s, z_m,
//                           pitch_deg, roll_deg (optional)
//
// Every kind also takes fps (10, frames per second), z_m (camera height, 1.0),
// pitch_noise_deg and roll_noise_deg (standard deviation of a smooth random tilt, 0) and
// noise_seed (1), and odometry_noise and odometry_seed (1): when odometry_noise is given (a
// relative standard deviation, 0..1), every pose also gets what wheel odometry would have
// measured (add_odometry). Positions default to the centre of the world's floor (or a margin inside
// it).

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "omninav/core/pose.hpp"
#include "omninav/sim/world.hpp"

namespace omninav::sim {

struct TimedPose {
  double time_s = 0.0;
  CameraPose pose;
  std::optional<std::array<int, 3>> grid;  // for grid sweeps: (ix, iy, 0)
  // What wheel odometry measured (dead reckoning from the first pose), when the spec asks for it.
  std::optional<CameraPose> odometry;
};

// The kinds of trajectory a spec names (the list above).
enum class TrajectoryKind {
  kRotate,
  kLine,
  kCircle,
  kWalk,
  kWander,
  kSaccade,
  kGrid,
  kZigzag,
  kTour,
  kCsv
};

std::string to_string(TrajectoryKind kind);
// The kind a spec's name gives, or nothing for an unknown name.
std::optional<TrajectoryKind> trajectory_kind_from_string(std::string_view text);

struct Trajectory {
  TrajectoryKind kind = TrajectoryKind::kRotate;
  std::vector<TimedPose> poses;
  double length_m() const;  // distance travelled on the floor
};

// Builds the trajectory a spec describes in `world`. Throws UsageError naming the bad key or
// value (and listing the valid keys), InputError for a bad CSV file.
Trajectory make_trajectory(const std::string& spec, const World& world);

// Wheel odometry along `poses`: each step's motion in the robot's frame (forward and sideways
// distance, turn) as measured, integrated from the first true pose (dead reckoning). The
// measured distance and turn of a step are the true ones times (1 + e_d) and (1 + e_t), e_d and
// e_t drawn from N(0, noise) afresh for every metre travelled (a wheel's slip and a tyre's
// wear persist over a stretch; Menegatti et al. 2004 §3.4: the distance between images known
// within 10 %). noise 0 gives the truth. Sets every pose's `odometry`.
void add_odometry(std::vector<TimedPose>& poses, double noise, std::uint64_t seed);

}  // namespace omninav::sim
