// libFuzzer target: a ROS 1 bag (libs/io through Debian's librosbag and cv_bridge), read whole
// as its one image topic, with and without poses from /odom or /pose. Seeds: tests/fuzz/corpus/
// ros1_bag, small bags of the route database written by tests/io/bags/write_ros1_bag.py
// (raw bgr8 images with Odometry; PNG CompressedImages with PoseStamped in lz4 chunks).
#include "fuzz_support.hpp"
#include "omninav/io/bag_sequence.hpp"
#include "omninav/io/sequence.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace omninav;
  static const std::filesystem::path bag = fuzz::scratch_dir() / "bag.bag";
  fuzz::write_file(bag, fuzz::as_text(data, size));
  for (const char* pose_topic : {"", "/odom", "/pose"}) {
    fuzz::expect_clean([pose_topic] {
      std::unique_ptr<io::SequenceReader> reader =
          io::open_bag(bag, {.topic = "", .pose_topic = pose_topic});
      (void)reader->describe();
      io::read_all(*reader);
    });
  }
  return 0;
}
