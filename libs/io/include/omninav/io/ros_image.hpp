#pragma once
// The picture of a ROS image message, as the bag readers (docs/bags.md, "Message types and
// encodings") and the ROS node (apps/omninav_ros) decode it: one conversion for recorded and
// live frames. Kept to C++17, for the files that include ROS 1's message headers (their
// std::allocator<void>::rebind is gone from C++20).

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace omninav::io {

// A sensor_msgs/Image's fields, as any format's decoder fills them.
struct RawImage {
  std::uint32_t height = 0;
  std::uint32_t width = 0;
  std::string encoding;
  bool is_bigendian = false;
  std::uint32_t step = 0;
  std::vector<std::uint8_t> data;
};

// The picture of a sensor_msgs/Image (through Debian's cv_bridge: colour encodings to bgr8,
// mono and 16-bit to mono8 scaled to 8 bits, Bayer patterns demosaiced to bgr8) or of a
// sensor_msgs/CompressedImage (cv::imdecode). Throws InputError prefixed with `where`: an
// unknown encoding, data shorter than its rows, more than 8192×8192 pixels.
cv::Mat decode_raw_image(RawImage image, const std::string& where);
cv::Mat decode_compressed_image(const std::vector<std::uint8_t>& data, const std::string& format,
                                const std::string& where);

}  // namespace omninav::io
