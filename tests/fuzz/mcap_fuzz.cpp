// libFuzzer target: a ROS 2 MCAP bag (libs/io's own MCAP and CDR readers), read whole as its
// one image topic, with and without poses from /odom or /pose. Seeds: tests/io/bags' MCAP files.
#include "read_bag.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return omninav::fuzz::read_as_bag(data, size, "bag.mcap");
}
