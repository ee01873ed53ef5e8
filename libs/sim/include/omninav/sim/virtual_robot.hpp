#pragma once
// A virtual robot for closed-loop experiments in a World: it turns and drives forward with
// configurable speed, turn rate and motion noise, and cannot pass through walls or furniture.
// Its true pose is known exactly (for evaluation only: the navigator never reads it).

#include <cstdint>
#include <opencv2/core.hpp>

#include "omninav/core/pose.hpp"
#include "omninav/sim/world.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::sim {

struct RobotParams {
  double speed_m_s = 0.2;         // forward speed
  double turn_rate_deg_s = 90.0;  // largest turning speed
  double turn_noise_deg = 2.0;    // standard deviation of the error of each turn
  double distance_noise = 0.05;   // standard deviation of the relative error of each move
  double radius_m = 0.15;         // clearance kept from walls and furniture
  std::uint32_t seed = 1;         // motion noise is seeded: runs are reproducible
};

// Reads the `robot:` section of navigation.yaml.
void load_robot_params(const ConfigReader& section, RobotParams& params);

class VirtualRobot {
 public:
  VirtualRobot(const World& world, const CameraPose& start, const RobotParams& params);

  const CameraPose& pose() const { return pose_; }
  double elapsed_s() const { return elapsed_s_; }

  // Turns by `turn_rad` (counter-clockwise positive), then drives `distance_m` forward, both
  // with noise; stops short of walls and furniture. Returns the distance actually driven.
  double move(double turn_rad, double distance_m);

 private:
  const World& world_;
  RobotParams params_;
  CameraPose pose_;
  cv::RNG rng_;
  double elapsed_s_ = 0.0;
};

}  // namespace omninav::sim
