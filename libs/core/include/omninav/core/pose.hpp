#pragma once
// Poses in the world frame: x, y on the floor, z up; heading counter-clockwise from +x
// (ROS REP 103 yaw). Pitch and roll follow REP 103 too: positive pitch turns the nose down,
// positive roll turns the left side up.
//
// Every 2-D position in the libraries is an Eigen::Vector2d (one type for one idea); where a
// position could be in two frames, its name says which (`world_position`, `lattice_position`).
// OpenCV's points appear only where pictures are drawn (measures, report).

#include <Eigen/Core>
#include <cmath>

namespace omninav {

// A robot's pose on the floor.
struct Pose2 {
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_rad = 0.0;

  Eigen::Vector2d position() const { return {x_m, y_m}; }
};

// A camera's full pose, as the renderer and ground-truth files give it.
struct CameraPose {
  double x_m = 0.0;
  double y_m = 0.0;
  double z_m = 0.0;
  double heading_rad = 0.0;  // yaw about +z
  double pitch_rad = 0.0;    // about the robot's +y (its left)
  double roll_rad = 0.0;     // about the robot's +x (its front)

  Pose2 on_floor() const { return {x_m, y_m, heading_rad}; }
  Eigen::Vector2d floor_position() const { return {x_m, y_m}; }
};

// The farthest from the origin a position may be, in metres, along any axis: 10,000 km, beyond
// any map a robot makes. Farther is a typing mistake or damage (a truth of 1e160 mm): refused
// where positions are read (check_coordinate_m in parse.hpp), and where distances are measured
// (figures, the lattice's evaluation) for maps built in memory, instead of overflowing them.
inline constexpr double kMaxCoordinateM = 1e7;

inline bool plausible_position(const CameraPose& pose) {
  return std::fabs(pose.x_m) <= kMaxCoordinateM && std::fabs(pose.y_m) <= kMaxCoordinateM &&
         std::fabs(pose.z_m) <= kMaxCoordinateM;  // false for NaN
}

}  // namespace omninav
