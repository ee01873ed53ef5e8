// ROS 2 MCAP bags written by the npm registry's @mcap/core and @foxglove/rosmsg2-serialization
// (tests/io/bags/write_mcap.mjs; the files are committed) from the rendered route database,
// read back frame for frame.

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "bag_test_support.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/io/panorama_input.hpp"

namespace omninav::io {
namespace {

using testing::expect_route;
using testing::kBagData;
using testing::Pixels;
using testing::read_bag;
using testing::TempDir;

TEST(McapBag, UncompressedChunksOfRgb8ImagesWithOdometry) {
  expect_route(read_bag(kBagData / "route_raw.mcap", {.topic = "", .pose_topic = "/odom"}),
               Pixels::kColour, true);
  expect_route(read_bag(kBagData / "route_raw.mcap", {}), Pixels::kColour, false);
}

TEST(McapBag, ZstdChunksOfCompressedImagesWithPoseStamped) {
  expect_route(read_bag(kBagData / "route_zstd.mcap", {.topic = "", .pose_topic = "/pose"}),
               Pixels::kColour, true);
}

TEST(McapBag, Lz4ChunksWithTwoImageTopicsNeedTopic) {
  const std::filesystem::path bag = kBagData / "route_lz4.mcap";
  EXPECT_INPUT_ERROR(read_bag(bag, {}), "route_lz4.mcap", "several image topics",
                     "/camera/image_raw", "/camera2/image_raw", "--topic");
  expect_route(read_bag(bag, {.topic = "/camera/image_raw", .pose_topic = "/odom"}), Pixels::kGrey,
               true);  // mono16
  expect_route(read_bag(bag, {.topic = "/camera2/image_raw", .pose_topic = ""}), Pixels::kColour,
               false);
  EXPECT_INPUT_ERROR(
      read_bag(bag, {.topic = "/camera/image_raw", .pose_topic = "/camera2/image_raw"}),
      "/camera2/image_raw", "not nav_msgs/Odometry");
}

TEST(McapBag, TruncatedFileGivesTheFramesBeforeTheCutThenSaysWhere) {
  const TempDir dir;
  const std::filesystem::path bag = dir / "cut.mcap";
  std::filesystem::copy_file(kBagData / "route_raw.mcap", bag);
  std::filesystem::resize_file(bag, std::filesystem::file_size(bag) * 6 / 10);
  const std::vector<Frame> frames =
      testing::read_until_error(bag, {.topic = "", .pose_topic = "/odom"}, "truncated");
  ASSERT_EQ(frames.size(), 6u);  // the cut is in the chunk after the sixth image's
  // The sixth image's pose, written after it, was lost, and is not extrapolated.
  const std::vector<Frame> posed(frames.begin(), frames.end() - 1);
  expect_route(posed, Pixels::kColour, true, posed.size());
  EXPECT_FALSE(frames.back().truth.has_value());
  EXPECT_TRUE(testing::same_pixels(frames.back().image, testing::route_frames()[5].image));
}

// route_raw.mcap with the byte at `offset` changed (its layout: the first chunk at byte 65, its
// records from byte 114; the fourth chunk at byte 9150, its records from 9199).
std::filesystem::path damaged_copy(const TempDir& dir, std::size_t offset, char byte) {
  const std::filesystem::path bag = dir / "damaged.mcap";
  std::filesystem::copy_file(kBagData / "route_raw.mcap", bag);
  std::fstream file(bag, std::ios::in | std::ios::out | std::ios::binary);
  file.seekp(static_cast<std::streamoff>(offset));
  file.put(byte);
  return bag;
}

TEST(McapBag, AChunkWhoseRecordsDoNotMatchItsCrcIsDamage) {
  const TempDir dir;
  // A pixel of the fourth chunk's image: every field still parses, only the CRC-32 tells.
  const std::filesystem::path bag = damaged_copy(dir, 9199 + 2000, '\x5a');
  const std::vector<Frame> frames =
      testing::read_until_error(bag, {.topic = "", .pose_topic = ""}, "byte 9150 is damaged");
  EXPECT_EQ(frames.size(), 3u);  // the images of the three chunks before it
}

TEST(McapBag, DamageInTheFirstRecordsIsReportedAsDamageNotAsNoTopics) {
  const TempDir dir;
  // The first record's length in the first chunk (which holds the schemas and channels).
  const std::filesystem::path bag = damaged_copy(dir, 114 + 8, '\x7f');
  try {
    read_bag(bag, {});
    ADD_FAILURE() << "read a damaged bag";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("damaged.mcap: the chunk at byte 65"), std::string::npos) << message;
    EXPECT_EQ(message.find("its topics"), std::string::npos) << message;
  }
}

TEST(McapBag, Ros2BagFolderThroughPanoramaInput) {
  const TempDir dir;
  const std::filesystem::path folder = dir / "run";
  std::filesystem::create_directories(folder);
  std::filesystem::copy_file(kBagData / "route_zstd.mcap", folder / "run_0.mcap");
  testing::write_text(folder / "metadata.yaml",
                      "rosbag2_bagfile_information:\n  storage_identifier: mcap\n");
  PanoramaInput input(folder, [] { return omni::UnwrapParams{}; },
                      {.topic = "/camera/image_raw/compressed", .pose_topic = "/pose"});
  EXPECT_EQ(input.size(), 9u);
  std::vector<Frame> frames;
  while (std::optional<Frame> frame = input.next()) frames.push_back(std::move(*frame));
  expect_route(frames, Pixels::kColour, true);
  EXPECT_NE(frames[2].source.find("/camera/image_raw/compressed frame 2"), std::string::npos)
      << frames[2].source;
}

TEST(McapBag, RawOmnidirectionalFramesAreUnwrappedAsAnyInputs) {
  omni::UnwrapParams camera;  // a small mirror in the route's 48 x 12 frames
  camera.units = omni::LengthUnits::kPixels;
  camera.centre_x = 24.0;
  camera.centre_y = 6.0;
  camera.inner_radius = 1.0;
  camera.outer_radius = 5.5;
  camera.width_px = 36;
  camera.height_px = 4;
  PanoramaInput input(kBagData / "route_raw.mcap", [&camera] { return camera; },
                      {.force_unwrap = true});
  const std::vector<Frame> route = testing::route_frames();
  const omni::Unwrapper unwrapper = omni::make_unwrapper(camera, route[0].image);
  std::size_t count = 0;
  while (std::optional<Frame> frame = input.next()) {
    ASSERT_LT(count, route.size());
    EXPECT_TRUE(testing::same_pixels(frame->image, unwrapper.unwrap(route[count].image)))
        << frame->source;
    ++count;
  }
  EXPECT_EQ(count, route.size());
}

TEST(McapBag, ReadingSlowlyGivesTheSameFrames) {
  // Nothing in the reading depends on the wall clock: frames read with pauses between them
  // (a slow consumer) are the frames read at full speed.
  const std::vector<Frame> fast =
      read_bag(kBagData / "route_zstd.mcap", {.topic = "", .pose_topic = "/pose"});
  std::unique_ptr<SequenceReader> reader =
      open_bag(kBagData / "route_zstd.mcap", {.topic = "", .pose_topic = "/pose"});
  std::vector<Frame> slow;
  while (std::optional<Frame> frame = reader->next()) {
    slow.push_back(std::move(*frame));
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
  ASSERT_EQ(slow.size(), fast.size());
  for (std::size_t i = 0; i < fast.size(); ++i) {
    EXPECT_TRUE(testing::same_pixels(slow[i].image, fast[i].image));
    EXPECT_EQ(slow[i].time_s, fast[i].time_s);
    EXPECT_EQ(slow[i].truth->heading_rad, fast[i].truth->heading_rad);
  }
}

}  // namespace
}  // namespace omninav::io
