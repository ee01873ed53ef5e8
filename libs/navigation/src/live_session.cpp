#include "omninav/navigation/live_session.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/phase_heading.hpp"

namespace omninav::navigation {

namespace {
// A part of a command (rad, m) with less than this left is done: odometry's rounding (a
// command's turn read back from a yaw), not a tolerance of the robot's.
constexpr double kDoneWithin = 1e-6;
}  // namespace

const char* to_string(SkipReason reason) {
  switch (reason) {
    case SkipReason::kBadImage:
      return "bad image";
    case SkipReason::kSizeChange:
      return "size change";
    case SkipReason::kStamp:
      return "stamp not increasing";
  }
  return "?";
}

const char* to_string(LiveNavigationState state) {
  switch (state) {
    case LiveNavigationState::kDriving:
      return "driving";
    case LiveNavigationState::kReached:
      return "reached";
    case LiveNavigationState::kFailed:
      return "failed";
  }
  return "?";
}

LiveSession::LiveSession(LiveSessionParams params, std::optional<std::filesystem::path> map_file)
    : params_(std::move(params)),
      map_file_(std::move(map_file)),
      compass_(params_.compass, params_.compass_width_px) {
  if (map_file_) {
    store_ = std::make_unique<memory::MapStore>(*map_file_);
    std::error_code error;
    memory_ = std::filesystem::exists(*map_file_, error)
                  ? std::make_unique<memory::VisualMemory>(store_->load())
                  : std::make_unique<memory::VisualMemory>(params_.memory.map);
  } else {
    memory_ = std::make_unique<memory::VisualMemory>(params_.memory.map);
  }
  if (memory_->place_count() == 0) {
    no_belief_reason_ = map_file_ ? "the map has no places" : "no map";
    return;
  }
  try {
    // The localiser, for goal images, is made when the session first navigates; the belief
    // reads the signatures, the links and their median.
    setup_ = goal_navigation_setup(*memory_, {}, params_.route, params_.navigator, params_.links,
                                   params_.belief, params_.steering);
  } catch (const UsageError& error) {  // no lattice, a place without a heading
    no_belief_reason_ = error.what();
    return;
  }
  const std::size_t count = setup_->places.size();
  belief_ = std::make_unique<PlaceBelief>(
      count, setup_->links, setup_->belief.view_scale * setup_->link_dissimilarity, setup_->belief);
  dissimilarity_.assign(count, 0.0);
  in_place_.assign(count, std::numeric_limits<double>::quiet_NaN());
  motion_.assign(count, std::numeric_limits<double>::quiet_NaN());
}

LiveSession::~LiveSession() = default;

std::size_t LiveSession::place_count() const {
  return memory_->place_count();
}

bool LiveSession::accept(const LiveFrame& frame) {
  std::optional<std::pair<SkipReason, std::string>> skip;
  const cv::Mat& image = frame.image;
  const int rows = memory_->parameters().panorama_rows;
  if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3)) {
    skip.emplace(SkipReason::kBadImage, "not an 8-bit grey or BGR image");
  } else if (frames_ > 0 && (image.size() != size_ || image.type() != type_)) {
    skip.emplace(SkipReason::kSizeChange,
                 std::to_string(image.cols) + "x" + std::to_string(image.rows) + " with " +
                     std::to_string(image.channels()) + " channels where the stream's first is " +
                     std::to_string(size_.width) + "x" + std::to_string(size_.height) + " with " +
                     std::to_string(CV_MAT_CN(type_)));
  } else if (rows > 0 && image.rows != rows) {
    skip.emplace(SkipReason::kSizeChange, std::to_string(image.rows) +
                                              " rows where the map's panoramas have " +
                                              std::to_string(rows));
  } else if (!std::isfinite(frame.stamp_s) || (last_stamp_s_ && frame.stamp_s <= *last_stamp_s_)) {
    skip.emplace(SkipReason::kStamp, "stamp " + std::to_string(frame.stamp_s) +
                                         " s is not after the last frame's " +
                                         std::to_string(last_stamp_s_.value_or(0.0)) + " s");
  }
  if (!skip) return true;
  ++skipped_[static_cast<int>(skip->first)];
  last_skip_ = std::move(skip);
  return false;
}

std::optional<LiveOutput> LiveSession::push(const LiveFrame& frame) {
  if (!accept(frame)) return std::nullopt;
  if (frames_ == 0) {
    size_ = frame.image.size();
    type_ = frame.image.type();
  }
  last_stamp_s_ = frame.stamp_s;
  const std::string source = "frame " + std::to_string(frames_);
  LiveOutput output;
  output.frame = frames_;
  output.stamp_s = frame.stamp_s;
  const std::optional<double> start_heading =
      frame.odometry ? std::optional<double>(frame.odometry->heading_rad) : std::nullopt;
  output.compass = compass_.push(frame.image, frames_, source, start_heading);
  output.place = recognise(frame.image, frame.odometry);
  output.command = command(frame);
  last_odometry_ = frame.odometry;
  ++frames_;
  if (explorer_) {
    io::Frame explored;
    explored.index = explored_frames_++;
    explored.time_s = frame.stamp_s;
    explored.image = frame.image;
    explored.source = source;
    if (frame.odometry) {
      explored.odometry = CameraPose{
          frame.odometry->x_m, frame.odometry->y_m, 0.0, frame.odometry->heading_rad, 0.0, 0.0};
    }
    output.new_place = explorer_->add(explored);
  }
  return output;
}

std::optional<LivePlace> LiveSession::recognise(const cv::Mat& panorama,
                                                const std::optional<Pose2>& odometry) {
  if (!belief_) return std::nullopt;
  const signature::Signature view = setup_->signature_of(panorama);
  place_dissimilarities(*setup_, view, dissimilarity_);
  // The motion since the last frame, seen from each place: its direction relative to the robot's
  // heading then (odometry), plus that frame's heading relative to the place (phases).
  double driven_m = 0.0;
  if (odometry && last_odometry_) {
    const double dx = odometry->x_m - last_odometry_->x_m;
    const double dy = odometry->y_m - last_odometry_->y_m;
    driven_m = std::hypot(dx, dy);
    const double direction = signed_difference(std::atan2(dy, dx), last_odometry_->heading_rad);
    for (std::size_t p = 0; p < motion_.size(); ++p) {
      motion_[p] = wrap_angle(in_place_[p] + direction);
    }
    belief_->predict(motion_, driven_m);
  } else if (frames_ > 0) {
    belief_->predict(motion_, 0.0);  // NaN motions: only the uniform share
  }
  // With odometry, a robot that did not move sees what it saw: no new evidence (navigator.cpp).
  if (!(odometry && last_odometry_) || driven_m > 0.0) belief_->update(dissimilarity_);
  for (std::size_t p = 0; p < in_place_.size(); ++p) {
    in_place_[p] = signature::relative_heading(setup_->signatures[p], view).turn_rad;
  }
  const int best = belief_->most_likely();
  LivePlace place;
  place.place = static_cast<memory::PlaceIndex>(best);
  place.similarity = signature::rescale_similarities(dissimilarity_)[best];
  place.dissimilarity_per_value = dissimilarity_[best];
  place.probability = belief_->probability(best);
  place.confidence = belief_->neighbourhood_probability(best);
  place.lost = belief_->lost();
  return place;
}

memory::PlaceMatch LiveSession::navigate_to(const cv::Mat& goal_image, const std::string& what) {
  if (!belief_) throw UsageError("cannot navigate: " + no_belief_reason_.value_or(""));
  if (!localiser_) {
    extractor_ = std::make_unique<signature::SignatureExtractor>(memory_->parameters().signature);
    localiser_ = std::make_unique<memory::Localiser>(*memory_, params_.memory.localisation);
    setup_->localise = memory_localiser(*localiser_, *extractor_);
  }
  const memory::PlaceMatch goal = recognise_goal(*setup_, goal_image, what);
  drive_ = std::make_unique<GoalDrive>(*setup_, static_cast<int>(goal.place),
                                       goal_homing(goal_image, setup_->homing));
  under_way_.reset();
  last_command_ = LiveCommand{};
  log_info("navigating to " + what + ", place " + std::to_string(goal.place));
  return goal;
}

void LiveSession::stop_navigating() {
  drive_.reset();
  under_way_.reset();
}

std::optional<LiveCommand> LiveSession::command(const LiveFrame& frame) {
  if (!drive_) return std::nullopt;
  if (under_way_) {
    LiveCommand left = last_command_;
    left.new_step = false;
    if (frame.odometry && under_way_->start) {
      if (!command_done(*frame.odometry, left)) return last_command_ = left;
    } else {
      // No odometry to follow it by: the caller carried the command out before this frame.
      drive_->moved(under_way_->command.distance_m);
    }
    under_way_.reset();
  }
  LiveCommand next = last_command_;
  next.new_step = false;
  next.turn_rad = 0.0;
  next.distance_m = 0.0;
  if (drive_->finished()) {
    next.state =
        drive_->result().reached ? LiveNavigationState::kReached : LiveNavigationState::kFailed;
    return last_command_ = next;
  }
  const DriveCommand command = drive_->step(frame.image);
  next.step = command.step.index;
  next.new_step = true;
  next.phase = command.step.phase;
  next.place = command.step.match->place;
  next.lost = command.step.lost;
  if (command.moves) {
    next.state = LiveNavigationState::kDriving;
    next.turn_rad = command.turn_rad;
    next.distance_m = command.distance_m;
    under_way_ = CommandUnderWay{command, frame.odometry, frame.odometry.value_or(Pose2{})};
  } else {
    next.state = LiveNavigationState::kReached;
  }
  return last_command_ = next;
}

bool LiveSession::command_done(const Pose2& odometry, LiveCommand& left) {
  CommandUnderWay& command = *under_way_;
  const Pose2& start = *command.start;
  const double turn_rad = command.command.turn_rad;
  // Turned by the command's turn, or past it: the odometry's yaw summed from frame to frame
  // (each along the shorter arc), so that a robot turning the other way never gets there.
  command.turned_rad += signed_difference(odometry.heading_rad, command.last.heading_rad);
  command.last = odometry;
  const double still_to_turn = turn_rad - command.turned_rad;
  const bool was_turned = command.turned;
  command.turned =
      command.turned || still_to_turn * turn_rad <= 0.0 || std::fabs(still_to_turn) < kDoneWithin;
  const double driven_m = std::hypot(odometry.x_m - start.x_m, odometry.y_m - start.y_m);
  // Turned before the last frame and not moved since: something stops the robot.
  const bool blocked = was_turned && last_odometry_ && odometry.x_m == last_odometry_->x_m &&
                       odometry.y_m == last_odometry_->y_m;
  if ((command.turned && driven_m >= command.command.distance_m - kDoneWithin) || blocked) {
    drive_->moved(driven_m);
    return true;
  }
  left.turn_rad = command.turned ? 0.0 : still_to_turn;
  left.distance_m = std::max(0.0, command.command.distance_m - driven_m);
  return false;
}

void LiveSession::start_exploring() {
  if (explorer_) return;
  explored_frames_ = 0;
  explorer_ = std::make_unique<memory::Explorer>(*memory_, params_.memory.exploration, "live",
                                                 "live session");
  log_info("exploring into " + (map_file_ ? map_file_->string() : std::string("a map in memory")));
}

void LiveSession::stop_exploring() {
  if (!explorer_) return;
  log_info("explored " + std::to_string(explorer_->frames_seen()) + " frames: the map has " +
           std::to_string(memory_->place_count()) + " places");
  explorer_.reset();
}

void LiveSession::save() {
  if (!store_) throw UsageError("the session has no map file to save to");
  store_->save(*memory_);
}

}  // namespace omninav::navigation
