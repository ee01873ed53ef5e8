#pragma once
// What every bag format gives BagSequence (bag_sequence.cpp): its topics, the poses of a pose
// topic, and the images of an image topic one by one. Kept to C++17 because ros1_bag.cpp, which
// includes it, is compiled as C++17: ROS 1's generated message headers use
// std::allocator<void>::rebind, which C++20 removed.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "omninav/io/bag_sequence.hpp"
#include "omninav/io/ros_image.hpp"

namespace omninav::io::detail {

struct BagTopic {
  std::string name;
  std::string type;  // as the bag names it: "sensor_msgs/Image" (ROS 1), "sensor_msgs/msg/Image"
  std::size_t count = 0;  // messages, as far as the bag could be read
};

// One image message: its header stamp and the picture, 8-bit BGR or grey.
struct BagImage {
  double stamp_s = 0.0;
  cv::Mat image;
};

class BagBackend {
 public:
  virtual ~BagBackend() = default;
  // "ROS 1 bag", "MCAP", "ROS 2 SQLite bag".
  virtual std::string kind() const = 0;
  virtual std::vector<BagTopic> topics() = 0;
  // The poses on `topic` (Odometry or PoseStamped), in the bag's order; those before any damage.
  virtual std::vector<StampedPose> poses(const std::string& topic) = 0;
  // Reads the images of `topic` from the start.
  virtual void start_images(const std::string& topic) = 0;
  // The next image, or nothing at the end; throws InputError at damage, after the images before.
  virtual std::optional<BagImage> next_image() = 0;
  // The message of the damage met while listing the topics, if any: when it hides the topic
  // asked for (damage in the first records), it is the error to report.
  virtual std::optional<std::string> damage() const { return std::nullopt; }
};

bool is_image_type(const std::string& type);
bool is_image_compressed_type(const std::string& type);
bool is_odometry_type(const std::string& type);
bool is_pose_stamped_type(const std::string& type);

std::unique_ptr<BagBackend> open_ros1_bag(const std::filesystem::path& file);
std::unique_ptr<BagBackend> open_mcap(const std::filesystem::path& file);
std::unique_ptr<BagBackend> open_db3(const std::filesystem::path& file);

}  // namespace omninav::io::detail
