#include "ros_session.hpp"

#include <cmath>

#include "cli.hpp"
#include "omninav/config/config_folder.hpp"
#include "omninav/io/bag_sequence.hpp"
#include "omninav/io/image_file.hpp"
#include "omninav/navigation/live_session.hpp"

namespace omninav::ros_node {

RosSession::RosSession(const std::string& config_dir, const std::string& map_file,
                       bool use_odometry, std::size_t max_waiting)
    : session_(std::make_unique<navigation::LiveSession>(
          config::load_live_session_params(config_dir.empty() ? cli::default_config_dir()
                                                              : std::filesystem::path(config_dir)),
          map_file.empty() ? std::nullopt : std::optional<std::filesystem::path>(map_file))),
      use_odometry_(use_odometry),
      max_waiting_(std::max<std::size_t>(max_waiting, 1)) {}

RosSession::~RosSession() = default;

void RosSession::process(const Waiting& frame, bool with_pose,
                         std::vector<FrameOutputs>& completed) {
  navigation::LiveFrame live{frame.image, frame.stamp_s, std::nullopt};
  if (with_pose) {
    if (const std::optional<CameraPose> pose = io::interpolate_pose(poses_, frame.stamp_s)) {
      live.odometry = pose->on_floor();
    }
  }
  const std::optional<navigation::LiveOutput> output = session_->push(live);
  if (!output) return;
  FrameOutputs result;
  result.stamp_s = output->stamp_s;
  result.heading_rad = output->compass.heading_rad;
  result.heading_sigma_rad = output->compass.heading_sigma_rad;
  if (output->place) {
    result.has_place = true;
    result.place = static_cast<std::uint32_t>(output->place->place);
    result.similarity = output->place->similarity;
    result.dissimilarity_per_value = output->place->dissimilarity_per_value;
    result.probability = output->place->probability;
    result.confidence = output->place->confidence;
    result.lost = output->place->lost;
  }
  if (output->new_place) result.new_place = static_cast<std::uint32_t>(*output->new_place);
  if (const std::optional<navigation::LiveCommand>& command = output->command) {
    result.navigating = true;
    result.navigation_state = static_cast<int>(command->state);
    result.turn_rad = command->turn_rad;
    result.distance_m = command->distance_m;
    result.step = command->step;
    result.homing = command->phase == navigation::NavigationPhase::kHoming;
    result.acted_on = static_cast<std::uint32_t>(command->place);
    result.navigation_lost = command->lost;
  }
  completed.push_back(result);
}

void RosSession::drain(std::vector<FrameOutputs>& completed) {
  while (!waiting_.empty() && !poses_.empty() &&
         waiting_.front().stamp_s <= poses_.back().stamp_s) {
    process(waiting_.front(), true, completed);
    waiting_.pop_front();
  }
  // The poses still needed: from the last one at or before the oldest waiting image.
  if (!waiting_.empty() && poses_.size() > 1) {
    std::size_t keep = 0;
    while (keep + 1 < poses_.size() && poses_[keep + 1].stamp_s <= waiting_.front().stamp_s) ++keep;
    poses_.erase(poses_.begin(), poses_.begin() + static_cast<std::ptrdiff_t>(keep));
  } else if (waiting_.empty() && poses_.size() > 1) {
    poses_.erase(poses_.begin(), poses_.end() - 1);
  }
}

std::vector<FrameOutputs> RosSession::image(const cv::Mat& image, double stamp_s) {
  std::vector<FrameOutputs> completed;
  if (!use_odometry_) {
    process({image, stamp_s}, false, completed);
    return completed;
  }
  waiting_.push_back({image.clone(), stamp_s});
  drain(completed);
  if (waiting_.size() > max_waiting_) {
    process(waiting_.front(), false, completed);
    waiting_.pop_front();
  }
  return completed;
}

bool RosSession::odometry(const OdometryPose& pose, std::vector<FrameOutputs>& completed) {
  if (!poses_.empty() && pose.stamp_s <= poses_.back().stamp_s) return false;
  poses_.push_back(
      {pose.stamp_s, pose.x_m, pose.y_m, pose.z_m, pose.qx, pose.qy, pose.qz, pose.qw});
  drain(completed);
  return true;
}

Velocity velocity_for(const FrameOutputs& frame, double max_linear_m_s, double max_angular_rad_s) {
  Velocity velocity;
  if (!frame.navigating ||
      frame.navigation_state != static_cast<int>(navigation::LiveNavigationState::kDriving)) {
    return velocity;
  }
  if (frame.turn_rad != 0.0) {
    velocity.angular_rad_s = std::copysign(max_angular_rad_s, frame.turn_rad);
  } else if (frame.distance_m > 0.0) {
    velocity.linear_m_s = max_linear_m_s;
  }
  return velocity;
}

std::uint32_t RosSession::navigate_to(const std::string& goal_image_file) {
  const memory::PlaceMatch goal =
      session_->navigate_to(io::read_image(goal_image_file), goal_image_file);
  return static_cast<std::uint32_t>(goal.place);
}

void RosSession::stop_navigating() {
  session_->stop_navigating();
}

bool RosSession::navigating() const {
  return session_->navigating();
}

void RosSession::start_exploring() {
  session_->start_exploring();
}
void RosSession::stop_exploring() {
  session_->stop_exploring();
}
void RosSession::save() {
  session_->save();
}
std::size_t RosSession::place_count() const {
  return session_->place_count();
}

std::string RosSession::no_belief_reason() const {
  return session_->no_belief_reason().value_or("");
}

std::string RosSession::last_skip_reason() const {
  return session_->last_skip() ? navigation::to_string(session_->last_skip()->first) : "";
}

std::string RosSession::last_skip_message() const {
  return session_->last_skip() ? session_->last_skip()->second : "";
}

int RosSession::skipped() const {
  int total = 0;
  for (int reason = 0; reason < navigation::kSkipReasons; ++reason) {
    total += session_->skipped(static_cast<navigation::SkipReason>(reason));
  }
  return total;
}

}  // namespace omninav::ros_node
