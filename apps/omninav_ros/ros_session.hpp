#pragma once
// What the ROS node (omninav_ros.cpp) needs of the live session (navigation/live_session.hpp),
// in types a C++17 file can include: ROS 1's generated message headers do not compile as C++20
// (std::allocator<void>::rebind), the libraries' headers need C++20. Besides the types, one
// thing the session does not do: pairing images with odometry by their stamps, so that what
// the node publishes does not depend on which of the two topics' messages arrives first.

#include <cstdint>
#include <deque>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace omninav::navigation {
class LiveSession;
}
namespace omninav::io {
struct StampedPose;
}

namespace omninav::ros_node {

// One frame's outputs (LiveOutput).
struct FrameOutputs {
  double stamp_s = 0.0;
  double heading_rad = 0.0;  // unwrapped
  double heading_sigma_rad = 0.0;
  bool has_place = false;  // the map recognises places (has a lattice)
  std::uint32_t place = 0;
  double similarity = 0.0;
  double dissimilarity_per_value = 0.0;
  double probability = 0.0;
  double confidence = 0.0;
  bool lost = false;
  std::optional<std::uint32_t> new_place;  // exploring
  // Navigating (LiveCommand): where it stands and what is left of the navigator's command.
  bool navigating = false;
  int navigation_state = 0;      // 0 driving, 1 reached, 2 failed (LiveNavigationState's order)
  double turn_rad = 0.0;         // still to turn on the spot, counter-clockwise positive
  double distance_m = 0.0;       // still to drive forwards after it
  int step = 0;                  // the navigator's step the command is of
  bool homing = false;           // the navigator homes on the goal image
  std::uint32_t acted_on = 0;    // the place the navigator acted on
  bool navigation_lost = false;  // the navigator's belief was spread
};

// A velocity command: forwards in m/s, counter-clockwise in rad/s (geometry_msgs/Twist's
// linear.x and angular.z).
struct Velocity {
  double linear_m_s = 0.0;
  double angular_rad_s = 0.0;
};

// The velocity that carries out what is left of a frame's command: the turn on the spot at
// `max_angular_rad_s` in its direction, then the drive at `max_linear_m_s`; zero when nothing is
// left, reached or failed. A function of the frame's outputs only, not of when it comes: the
// session decides from the odometry when a part is done (live_session.hpp), so the robot
// overshoots a part by at most what it moves in one frame period.
Velocity velocity_for(const FrameOutputs& frame, double max_linear_m_s, double max_angular_rad_s);

// An odometry message's pose.
struct OdometryPose {
  double stamp_s = 0.0;
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;
  double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
};

class RosSession {
 public:
  // The session over `map_file` (empty: none) with the parameters of the configuration folder
  // `config_dir` (empty: the program's, as omninav's; load_live_session_params). With
  // `use_odometry`, each image waits for an odometry message stamped at or after it, and takes the
  // pose interpolated at its stamp (io::interpolate_pose, as the bag readers do); at most
  // `max_waiting` images wait, the oldest then goes on without a pose. Throws omninav's errors
  // (std::runtime_error).
  RosSession(const std::string& config_dir, const std::string& map_file, bool use_odometry,
             std::size_t max_waiting);
  ~RosSession();

  // The outputs of the frames this image (and the images waiting for odometry) completes, in
  // order; a frame the session skips gives none (skip_message says why).
  std::vector<FrameOutputs> image(const cv::Mat& image, double stamp_s);
  // Likewise for the frames an odometry message completes. An odometry message not after the
  // last is ignored (returns false).
  bool odometry(const OdometryPose& pose, std::vector<FrameOutputs>& completed);

  // Navigating to the panorama in `goal_image_file` (LiveSession::navigate_to); returns the
  // goal's place. Throws omninav's errors (the image unreadable, matching no place).
  std::uint32_t navigate_to(const std::string& goal_image_file);
  void stop_navigating();
  bool navigating() const;

  void start_exploring();
  void stop_exploring();
  void save();  // throws what the map store throws
  std::size_t place_count() const;
  // Why the map recognises no places, empty when it does.
  std::string no_belief_reason() const;
  // The last skip's reason ("size change", ...) and message; the count of every skip so far.
  std::string last_skip_reason() const;
  std::string last_skip_message() const;
  int skipped() const;

 private:
  struct Waiting {
    cv::Mat image;
    double stamp_s;
  };
  void process(const Waiting& frame, bool with_pose, std::vector<FrameOutputs>& completed);
  // Processes the waiting images that the odometry received covers.
  void drain(std::vector<FrameOutputs>& completed);

  std::unique_ptr<navigation::LiveSession> session_;
  bool use_odometry_;
  std::size_t max_waiting_;
  std::deque<Waiting> waiting_;
  std::vector<io::StampedPose> poses_;
};

}  // namespace omninav::ros_node
