#pragma once
// The ROS 2 messages omninav reads, decoded from their CDR serialisation (OMG XCDR1, as
// rosbag2 stores them: a 4-byte encapsulation header, little- or big-endian, primitives aligned
// to their size from the end of the header). Hand-written with mcap_reader and db3_reader:
// Debian packages no ROS 2 serialisation library (nor MCAP) to read bags with.

#include <cstdint>
#include <string>
#include <vector>

#include "bag_backend.hpp"

namespace omninav::io::detail {

// `where` names the message in errors ("run.mcap#/camera message 3").
// sensor_msgs/msg/Image and sensor_msgs/msg/CompressedImage, by `type`; throws InputError on a
// message too short or malformed.
BagImage decode_cdr_image(const std::string& type, const std::vector<std::uint8_t>& data,
                          const std::string& where);
// nav_msgs/msg/Odometry or geometry_msgs/msg/PoseStamped, by `type`.
StampedPose decode_cdr_pose(const std::string& type, const std::vector<std::uint8_t>& data,
                            const std::string& where);

}  // namespace omninav::io::detail
