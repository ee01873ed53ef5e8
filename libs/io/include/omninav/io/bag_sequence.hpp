#pragma once
// Robot recordings as image sequences (docs/bags.md lists the message types and encodings):
//   - ROS 1 bags (.bag), read with Debian's librosbag;
//   - ROS 2 bags, MCAP (.mcap, the default storage since Iron) or SQLite (.db3), or the bag's
//     folder holding metadata.yaml; read by our own code (mcap_reader, db3_reader, cdr), since
//     Debian packages no library for either.
// The frames are the messages of one image topic (sensor_msgs/Image or CompressedImage), in the
// order the bag stores them, with their header stamps as times. With a pose topic
// (nav_msgs/Odometry or geometry_msgs/PoseStamped) each frame's pose is the pose interpolated
// at its stamp. Nothing depends on the wall clock or on how fast the bag is read.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "omninav/core/pose.hpp"
#include "omninav/io/sequence.hpp"

namespace omninav::io {

struct BagOptions {
  std::string topic = {};       // the image topic; empty: the bag's only one
  std::string pose_topic = {};  // Odometry or PoseStamped; empty: no poses
};

// Whether `path` names a bag: a .bag, .mcap or .db3 file, or a folder holding metadata.yaml
// (a ROS 2 bag folder).
bool is_bag(const std::filesystem::path& path);

// Opens a bag. Throws InputError naming the bag: unknown or unreadable format, no image topic,
// a --topic that is not there or not images, several image topics and no --topic (naming
// them). A bag damaged part way (a truncated file) gives its frames up to the damage, then
// next() throws InputError saying where.
std::unique_ptr<SequenceReader> open_bag(const std::filesystem::path& path,
                                         const BagOptions& options);

// open_sequence(path), a bag opened with `options`; throws UsageError when `options` names a
// topic and `path` is not a bag.
std::unique_ptr<SequenceReader> open_sequence(const std::filesystem::path& path,
                                              const BagOptions& options);

// A pose at a stamp, from a pose topic: position and unit quaternion (x, y, z, w).
struct StampedPose {
  double stamp_s = 0.0;
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;
  double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
};

// The pose at `stamp_s` from `poses` (sorted by stamp): position linear between the two poses
// around it, heading (yaw) along the shorter arc between theirs, pitch and roll likewise; a
// stamp equal to a pose's gives that pose. Nothing before the first or after the last stamp.
std::optional<CameraPose> interpolate_pose(const std::vector<StampedPose>& poses, double stamp_s);

}  // namespace omninav::io
