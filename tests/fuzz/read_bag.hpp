#pragma once
// What the bag targets of tests/fuzz share (mcap, ros1_bag): the input read as a bag whole.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "fuzz_support.hpp"
#include "omninav/io/bag_sequence.hpp"
#include "omninav/io/sequence.hpp"

namespace omninav::fuzz {

// Writes `data` to scratch_dir()/<file_name> and reads it as a bag whole (its one image topic),
// without poses and with poses from /odom and from /pose.
inline int read_as_bag(const std::uint8_t* data, std::size_t size, const std::string& file_name) {
  const std::filesystem::path bag = scratch_dir() / file_name;
  write_file(bag, as_text(data, size));
  for (const char* pose_topic : {"", "/odom", "/pose"}) {
    expect_clean([&bag, pose_topic] {
      std::unique_ptr<io::SequenceReader> reader =
          io::open_bag(bag, {.topic = "", .pose_topic = pose_topic});
      (void)reader->describe();
      io::read_all(*reader);
    });
  }
  return 0;
}

}  // namespace omninav::fuzz
