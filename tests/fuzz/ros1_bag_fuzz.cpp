// libFuzzer target: a ROS 1 bag (libs/io through Debian's librosbag and cv_bridge), read whole
// as its one image topic, with and without poses from /odom or /pose. Seeds: tests/fuzz/corpus/
// ros1_bag, small bags of the route database written by tests/io/bags/write_ros1_bag.py
// (raw bgr8 images with Odometry; PNG CompressedImages with PoseStamped in lz4 chunks; PNG
// CompressedImages in bz2 chunks, the first message declaring more data than it holds), and the
// damaged bags of earlier findings (regression-*: an index entry beyond its lz4 chunk, ...).
#include "read_bag.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return omninav::fuzz::read_as_bag(data, size, "bag.bag");
}
