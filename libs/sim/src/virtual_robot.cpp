#include "omninav/sim/virtual_robot.hpp"

#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"

namespace omninav::sim {

void load_robot_params(const ConfigReader& section, RobotParams& params) {
  section.read("speed_m_s", params.speed_m_s, 0.01, 10.0);
  section.read("turn_rate_deg_s", params.turn_rate_deg_s, 1.0, 3600.0);
  section.read("turn_noise_deg", params.turn_noise_deg, 0.0, 45.0);
  section.read("distance_noise", params.distance_noise, 0.0, 1.0);
  section.read("radius_m", params.radius_m, 0.0, 5.0);
  int seed = static_cast<int>(params.seed);
  section.read("seed", seed, 0, 1'000'000'000);
  params.seed = static_cast<std::uint32_t>(seed);
}

VirtualRobot::VirtualRobot(const World& world, const CameraPose& start, const RobotParams& params)
    : world_(world), params_(params), pose_(start), rng_(params.seed) {}

double VirtualRobot::move(double turn_rad, double distance_m) {
  const double turn = turn_rad + deg_to_rad(rng_.gaussian(params_.turn_noise_deg));
  pose_.heading_rad = wrap_angle(pose_.heading_rad + turn);
  const double wanted = std::max(0.0, distance_m * (1.0 + rng_.gaussian(params_.distance_noise)));
  // Drive in small increments so that the robot stops at the first obstacle it would touch.
  constexpr double kIncrement_m = 0.01;
  double driven = 0.0;
  // A robot placed closer to an obstacle than its clearance may still drive away: then only
  // entering the obstacle itself stops it.
  const double clearance =
      world_.is_free(pose_.x_m, pose_.y_m, params_.radius_m) ? params_.radius_m : 0.0;
  while (driven < wanted) {
    const double increment = std::min(kIncrement_m, wanted - driven);
    const double x = pose_.x_m + increment * std::cos(pose_.heading_rad);
    const double y = pose_.y_m + increment * std::sin(pose_.heading_rad);
    // The whole increment, not only its end: a wall thinner than it must still stop the robot.
    if (!world_.segment_is_free(pose_.x_m, pose_.y_m, x, y, clearance)) break;
    pose_.x_m = x;
    pose_.y_m = y;
    driven += increment;
  }
  elapsed_s_ += std::abs(turn) / deg_to_rad(params_.turn_rate_deg_s) + driven / params_.speed_m_s;
  return driven;
}

}  // namespace omninav::sim
