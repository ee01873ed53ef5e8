#include "omninav/io/bag_sequence.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "bag_backend.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/io/image_file.hpp"

namespace omninav::io {
namespace detail {

// ROS 1 names a type "package/Name", ROS 2 "package/msg/Name".
bool is_type(const std::string& type, const std::string& package, const std::string& name) {
  return type == package + "/" + name || type == package + "/msg/" + name;
}
bool is_image_type(const std::string& type) {
  return is_type(type, "sensor_msgs", "Image") || is_image_compressed_type(type);
}
bool is_image_compressed_type(const std::string& type) {
  return is_type(type, "sensor_msgs", "CompressedImage");
}
bool is_odometry_type(const std::string& type) {
  return is_type(type, "nav_msgs", "Odometry");
}
bool is_pose_stamped_type(const std::string& type) {
  return is_type(type, "geometry_msgs", "PoseStamped");
}

}  // namespace detail

namespace {

using detail::BagTopic;

std::string lower_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// A ROS 2 bag folder's storage file: the one .mcap or .db3 in it (a split recording's parts
// are not joined).
std::filesystem::path storage_file_of(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> files;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    const std::string extension = lower_extension(entry.path());
    if (extension == ".mcap" || extension == ".db3") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    throw InputError(folder.string() + ": a ROS 2 bag folder (metadata.yaml) with no .mcap or " +
                     ".db3 file");
  }
  if (files.size() > 1) {
    throw InputError(folder.string() + ": a ROS 2 bag split into " + std::to_string(files.size()) +
                     " files (" + files.front().string() + ", ...); give one of them as --input");
  }
  return files.front();
}

std::string names_of(const std::vector<BagTopic>& topics) {
  std::string names;
  for (const BagTopic& topic : topics) {
    names += (names.empty() ? "" : ", ") + printable_name(topic.name) + " (" +
             printable_name(topic.type) + ")";
  }
  return names;
}

// The pose message `index` of `where` ("<bag>#/odom message 3"), checked as every pose is
// (check_pose): a finite stamp, a position within the bound, and an orientation that is a
// rotation (a quaternion of zeros, or not finite, says nothing of the heading).
void check_stamped_pose(const StampedPose& pose, const std::string& where) {
  if (!std::isfinite(pose.stamp_s)) {
    throw InputError(where + ": stamp " + general(pose.stamp_s) + " s is not a time");
  }
  const double norm =
      std::sqrt(pose.qx * pose.qx + pose.qy * pose.qy + pose.qz * pose.qz + pose.qw * pose.qw);
  if (!std::isfinite(norm) || norm < 1e-6) {
    throw InputError(where + ": orientation (" + general(pose.qx) + ", " + general(pose.qy) + ", " +
                     general(pose.qz) + ", " + general(pose.qw) +
                     ") is not a rotation (a quaternion of length 0 or not finite)");
  }
  check_pose({.x_m = pose.x_m, .y_m = pose.y_m, .z_m = pose.z_m}, where);
}

double yaw_of(const StampedPose& pose) {
  return std::atan2(2.0 * (pose.qw * pose.qz + pose.qx * pose.qy),
                    1.0 - 2.0 * (pose.qy * pose.qy + pose.qz * pose.qz));
}
double pitch_of(const StampedPose& pose) {
  return std::asin(std::clamp(2.0 * (pose.qw * pose.qy - pose.qz * pose.qx), -1.0, 1.0));
}
double roll_of(const StampedPose& pose) {
  return std::atan2(2.0 * (pose.qw * pose.qx + pose.qy * pose.qz),
                    1.0 - 2.0 * (pose.qx * pose.qx + pose.qy * pose.qy));
}

class BagSequence : public SequenceReader {
 public:
  BagSequence(const std::filesystem::path& path, std::unique_ptr<detail::BagBackend> backend,
              const BagOptions& options)
      : path_(path), backend_(std::move(backend)) {
    const std::vector<BagTopic> topics = backend_->topics();
    std::vector<BagTopic> image_topics;
    for (const BagTopic& topic : topics) {
      if (detail::is_image_type(topic.type)) image_topics.push_back(topic);
    }
    const std::string what = path.string() + ": ";
    if (!options.topic.empty()) {
      const auto found = std::find_if(topics.begin(), topics.end(),
                                      [&](const BagTopic& t) { return t.name == options.topic; });
      if (found == topics.end()) {
        if (const std::optional<std::string> damage = backend_->damage()) throw InputError(*damage);
        throw InputError(
            what + "no topic " + printable_name(options.topic) + " in the " + backend_->kind() +
            "; its image topics: " + (image_topics.empty() ? "none" : names_of(image_topics)));
      }
      if (!detail::is_image_type(found->type)) {
        throw InputError(what + "topic " + printable_name(options.topic) + " holds " +
                         printable_name(found->type) +
                         ", not sensor_msgs/Image or CompressedImage");
      }
      topic_ = *found;
    } else if (image_topics.empty()) {
      if (const std::optional<std::string> damage = backend_->damage()) throw InputError(*damage);
      throw InputError(what + "no image topic (sensor_msgs/Image or CompressedImage) in the " +
                       backend_->kind() + "; its topics: " + names_of(topics));
    } else if (image_topics.size() > 1) {
      throw InputError(what + "several image topics: " + names_of(image_topics) +
                       "; choose one with --topic");
    } else {
      topic_ = image_topics.front();
    }
    if (!options.pose_topic.empty()) {
      const auto found = std::find_if(topics.begin(), topics.end(), [&](const BagTopic& t) {
        return t.name == options.pose_topic;
      });
      if (found == topics.end()) {
        if (const std::optional<std::string> damage = backend_->damage()) throw InputError(*damage);
        throw InputError(what + "no topic " + printable_name(options.pose_topic) +
                         " (--pose-topic) in the " + backend_->kind());
      }
      if (!detail::is_odometry_type(found->type) && !detail::is_pose_stamped_type(found->type)) {
        throw InputError(what + "topic " + printable_name(options.pose_topic) + " holds " +
                         printable_name(found->type) +
                         ", not nav_msgs/Odometry or geometry_msgs/PoseStamped");
      }
      pose_topic_ = options.pose_topic;
      poses_ = backend_->poses(pose_topic_);
      for (std::size_t i = 0; i < poses_.size(); ++i) {
        check_stamped_pose(poses_[i], path.string() + "#" + printable_name(pose_topic_) +
                                          " message " + std::to_string(i));
      }
      std::stable_sort(
          poses_.begin(), poses_.end(),
          [](const StampedPose& a, const StampedPose& b) { return a.stamp_s < b.stamp_s; });
    }
    backend_->start_images(topic_.name);
  }

  std::optional<Frame> next() override {
    std::optional<detail::BagImage> image = backend_->next_image();
    if (!image) return std::nullopt;
    Frame frame;
    frame.index = next_index_;
    frame.time_s = image->stamp_s;
    frame.image = std::move(image->image);
    frame.source = path_.string() + "#" + printable_name(topic_.name) + " frame " +
                   std::to_string(next_index_);
    if (!pose_topic_.empty()) {
      frame.truth = interpolate_pose(poses_, image->stamp_s);
      frame.odometry = frame.truth;  // a robot's pose topic is its odometry
    }
    size_check_.check(frame.image, frame.source);
    ++next_index_;
    return frame;
  }

  std::size_t size() const override { return topic_.count; }

  std::string describe() const override {
    std::string text = backend_->kind() + " " + path_.string() + " (" +
                       printable_name(topic_.name) + ", " + std::to_string(topic_.count) +
                       " images";
    if (!pose_topic_.empty()) {
      text += ", poses from " + printable_name(pose_topic_) + " (" + std::to_string(poses_.size()) +
              ")";
    }
    return text + ")";
  }

 private:
  std::filesystem::path path_;
  std::unique_ptr<detail::BagBackend> backend_;
  BagTopic topic_;
  std::string pose_topic_;
  std::vector<StampedPose> poses_;
  int next_index_ = 0;
  ImageSizeCheck size_check_;
};

}  // namespace

bool is_bag(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    return std::filesystem::exists(path / "metadata.yaml", error);
  }
  const std::string extension = lower_extension(path);
  return extension == ".bag" || extension == ".mcap" || extension == ".db3";
}

std::unique_ptr<SequenceReader> open_bag(const std::filesystem::path& path,
                                         const BagOptions& options) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) {
    throw InputError(path.string() + ": no such bag");
  }
  const std::filesystem::path file =
      std::filesystem::is_directory(path, error) ? storage_file_of(path) : path;
  if (!std::filesystem::is_regular_file(file, error)) {
    throw InputError(file.string() + ": " + unreadable_file_reason(file, "bag file"));
  }
  const std::string extension = lower_extension(file);
  std::unique_ptr<detail::BagBackend> backend;
  if (extension == ".bag") {
    backend = detail::open_ros1_bag(file);
  } else if (extension == ".mcap") {
    backend = detail::open_mcap(file);
  } else if (extension == ".db3") {
    backend = detail::open_db3(file);
  } else {
    throw InputError(file.string() + ": not a bag (.bag, .mcap or .db3)");
  }
  return std::make_unique<BagSequence>(path, std::move(backend), options);
}

std::unique_ptr<SequenceReader> open_sequence(const std::filesystem::path& path,
                                              const BagOptions& options) {
  if (is_bag(path)) return open_bag(path, options);
  if (!options.topic.empty() || !options.pose_topic.empty()) {
    throw UsageError(path.string() + ": --topic and --pose-topic are for bags (.bag, .mcap, " +
                     ".db3, or a ROS 2 bag folder)");
  }
  return open_sequence(path);
}

std::optional<CameraPose> interpolate_pose(const std::vector<StampedPose>& poses, double stamp_s) {
  if (poses.empty() || stamp_s < poses.front().stamp_s || stamp_s > poses.back().stamp_s) {
    return std::nullopt;
  }
  const auto after =
      std::lower_bound(poses.begin(), poses.end(), stamp_s,
                       [](const StampedPose& pose, double stamp) { return pose.stamp_s < stamp; });
  const StampedPose& b = *after;
  const StampedPose& a = after == poses.begin() ? b : *(after - 1);
  const double span_s = b.stamp_s - a.stamp_s;
  const double t = (b.stamp_s == stamp_s || span_s <= 0.0) ? 1.0 : (stamp_s - a.stamp_s) / span_s;
  const auto mix = [t](double from, double to) { return from + t * (to - from); };
  const auto mix_angle = [t](double from, double to) {
    return wrap_angle(from + t * signed_difference(to, from));
  };
  CameraPose pose;
  pose.x_m = mix(a.x_m, b.x_m);
  pose.y_m = mix(a.y_m, b.y_m);
  pose.z_m = mix(a.z_m, b.z_m);
  pose.heading_rad = mix_angle(yaw_of(a), yaw_of(b));
  pose.pitch_rad = mix_angle(pitch_of(a), pitch_of(b));
  pose.roll_rad = mix_angle(roll_of(a), roll_of(b));
  return pose;
}

}  // namespace omninav::io
