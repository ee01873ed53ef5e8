// ROS 2 SQLite bags (.db3) written by Python's sqlite3 with a CDR writer of its own
// (tests/io/bags/write_ros2_db3.py) from the rendered route database, read back frame for frame.

#include <gtest/gtest.h>
#include <sqlite3.h>

#include "bag_test_support.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/io/panorama_input.hpp"

namespace omninav::io {
namespace {

using testing::expect_route;
using testing::Pixels;
using testing::read_bag;
using testing::TempDir;

// The bag's folder (with metadata.yaml); its storage file is <folder>/run.db3.
std::filesystem::path write_bag(const TempDir& dir, const std::string& arguments) {
  return testing::write_with("write_ros2_db3.py", dir / "run", arguments);
}

TEST(Db3Bag, TopicNamesThatAreNotUtf8AreEscapedInMessages) {
  const TempDir dir;
  const std::filesystem::path db3 = write_bag(dir, "--encoding bgr8") / "run.db3";
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(db3.c_str(), &db), SQLITE_OK);
  // "/cam", a control character, and a byte that is not UTF-8.
  ASSERT_EQ(sqlite3_exec(db, "UPDATE topics SET name = CAST(X'2F63616D18FF' AS TEXT)", nullptr,
                         nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  try {
    read_bag(db3, {.topic = "/camera/image_raw", .pose_topic = ""});
    ADD_FAILURE() << "found a topic that is not there";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("its image topics: /cam\\x18\\xff (sensor_msgs/msg/Image)"),
              std::string::npos)
        << message;
    EXPECT_EQ(message.find('\xff'), std::string::npos) << "raw bytes in: " << message;
  }
}

TEST(Db3Bag, RawImagesInEveryEncodingReadBackAsTheDatabase) {
  for (const std::string encoding : {"rgb8", "bgr8", "rgba8", "bgra8", "mono8", "mono16"}) {
    SCOPED_TRACE(encoding);
    const TempDir dir;
    const Pixels pixels = encoding.starts_with("mono") ? Pixels::kGrey : Pixels::kColour;
    expect_route(read_bag(write_bag(dir, "--encoding " + encoding) / "run.db3", {}), pixels, false);
  }
}

TEST(Db3Bag, CompressedImagesWithOdometryBigEndianThroughTheFolder) {
  const TempDir dir;
  const auto folder = write_bag(dir, "--encoding png --poses odometry --big-endian");
  PanoramaInput input(folder, [] { return omni::UnwrapParams{}; },
                      {.topic = "", .pose_topic = "/odom"});
  EXPECT_NE(input.describe().find("ROS 2 SQLite bag"), std::string::npos) << input.describe();
  std::vector<Frame> frames;
  while (std::optional<Frame> frame = input.next()) frames.push_back(std::move(*frame));
  expect_route(frames, Pixels::kColour, true);
}

TEST(Db3Bag, PoseStampedAndTwoImageTopics) {
  const TempDir dir;
  const auto bag = write_bag(dir, "--poses pose_stamped --second-camera") / "run.db3";
  EXPECT_INPUT_ERROR(read_bag(bag, {}), "run.db3", "several image topics", "/camera/image_raw",
                     "/camera2/image_raw");
  expect_route(read_bag(bag, {.topic = "/camera2/image_raw", .pose_topic = "/pose"}),
               Pixels::kColour, true);
}

TEST(Db3Bag, TruncatedFileGivesTheFramesBeforeTheDamageThenSaysSo) {
  const TempDir dir;
  // 9 images of 1.7 kB with their poses fill about 15 pages of 4 kB: cut after about half.
  const auto bag = write_bag(dir, "--poses odometry --truncate-bytes 36864") / "run.db3";
  const std::vector<Frame> frames =
      testing::read_until_error(bag, {.topic = "", .pose_topic = "/odom"}, "damaged");
  ASSERT_GE(frames.size(), 2u);
  ASSERT_LT(frames.size(), 9u);
  expect_route(frames, Pixels::kColour, true, frames.size());
}

}  // namespace
}  // namespace omninav::io
