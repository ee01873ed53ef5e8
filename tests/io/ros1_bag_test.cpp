// ROS 1 bags written by Debian's python3-rosbag (tests/io/bags/write_ros1_bag.py) from the
// rendered route database, read back frame for frame.

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "bag_test_support.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/io/panorama_input.hpp"
#include "support/png_header.hpp"

namespace omninav::io {
namespace {

using testing::expect_route;
using testing::kBagData;
using testing::Pixels;
using testing::read_bag;
using testing::TempDir;

std::filesystem::path write_bag(const TempDir& dir, const std::string& arguments) {
  return testing::write_with("write_ros1_bag.py", dir / "run.bag", arguments);
}

TEST(Ros1Bag, RawImagesInEveryColourEncodingReadBackAsTheDatabase) {
  for (const std::string encoding : {"rgb8", "bgr8", "rgba8", "bgra8"}) {
    SCOPED_TRACE(encoding);
    const TempDir dir;
    expect_route(read_bag(write_bag(dir, "--encoding " + encoding), {}), Pixels::kColour, false);
  }
}

TEST(Ros1Bag, GreyImagesEightAndSixteenBitsReadBackAsTheDatabasesGrey) {
  for (const std::string encoding : {"mono8", "mono16"}) {
    SCOPED_TRACE(encoding);
    const TempDir dir;
    expect_route(read_bag(write_bag(dir, "--encoding " + encoding), {}), Pixels::kGrey, false);
  }
}

TEST(Ros1Bag, CompressedImagesWithOdometryInCompressedChunks) {
  for (const std::string compression : {"lz4", "bz2"}) {
    SCOPED_TRACE(compression);
    const TempDir dir;
    const auto bag = write_bag(dir, "--encoding png --poses odometry --compression " + compression);
    expect_route(read_bag(bag, {.topic = "", .pose_topic = "/odom"}), Pixels::kColour, true);
  }
}

TEST(Ros1Bag, PoseStampedPosesThroughPanoramaInput) {
  const TempDir dir;
  const auto bag = write_bag(dir, "--encoding bgr8 --poses pose_stamped");
  PanoramaInput input(bag, [] { return omni::UnwrapParams{}; },
                      {.topic = "/camera/image_raw", .pose_topic = "/pose"});
  EXPECT_EQ(input.size(), 9u);
  EXPECT_NE(input.describe().find("ROS 1 bag"), std::string::npos) << input.describe();
  std::vector<Frame> frames;
  while (std::optional<Frame> frame = input.next()) frames.push_back(std::move(*frame));
  expect_route(frames, Pixels::kColour, true);
}

std::filesystem::path header_only_png(const TempDir& dir, std::uint32_t width,
                                      std::uint32_t height) {
  const std::filesystem::path file = dir / "header.png";
  omninav::testing::write_header_only_png(file, width, height);
  return file;
}

TEST(Ros1Bag, PosesBeyondTheBoundOrWithoutARotationAreRefusedNamingTheMessage) {
  for (const auto& [pose, why] : std::vector<std::pair<std::string, std::string>>{
           {"1e300,0,0,0,0,0,1", "x: 1e+300 m is not a position"},
           {"nan,0,0,0,0,0,1", "x: nan m is not a position"},
           {"1,2,0,0,0,0,0", "is not a rotation"}}) {
    SCOPED_TRACE(pose);
    const TempDir dir;
    const auto bag = write_bag(dir, "--encoding bgr8 --poses odometry --first-pose " + pose);
    EXPECT_INPUT_ERROR(read_bag(bag, {.topic = "", .pose_topic = "/odom"}),
                       "run.bag#/odom message 0", why);
  }
}

TEST(Ros1Bag, ACompressedImageDeclaringTooManyPixelsIsRefusedBeforeDecoding) {
  const TempDir dir;
  const auto bag =
      write_bag(dir, "--encoding png --png-file " + header_only_png(dir, 12000, 12000).string());
  EXPECT_INPUT_ERROR(read_bag(bag, {}), "run.bag#/camera/image_raw/compressed message 0",
                     "12000x12000 px", "more than omninav reads");
}

TEST(Ros1Bag, ABrokenCompressedImageGivesOurLineAndNoLibpngLine) {
  const TempDir dir;
  const auto bag =
      write_bag(dir, "--encoding png --png-file " + header_only_png(dir, 8, 4).string());
  ::testing::internal::CaptureStderr();
  EXPECT_INPUT_ERROR(read_bag(bag, {}), "message 0", "cannot decode the compressed image");
  const std::string stderr_text = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(stderr_text.find("libpng"), std::string::npos) << stderr_text;
}

TEST(Ros1Bag, ARecordDeclaringMoreBytesThanTheFileIsDamageNotAnAllocation) {
  // The fuzzer's finding: librosbag allocated the 4 GB header a record of a 40 KB bag declared.
  const TempDir dir;
  const auto bag = write_bag(dir, "--encoding bgr8");
  std::string bytes;
  {
    std::ifstream in(bag, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  // The bag header's index_pos (8 bytes little-endian after "index_pos="): the first record of
  // the index, a connection record, gets a header length of 0xFFFFFFFF.
  const std::size_t field = bytes.find("index_pos=");
  ASSERT_NE(field, std::string::npos);
  std::uint64_t index_pos = 0;
  for (int i = 7; i >= 0; --i) {
    index_pos = index_pos << 8 | static_cast<unsigned char>(bytes[field + 10 + i]);
  }
  ASSERT_LT(index_pos + 4, bytes.size());
  bytes.replace(index_pos, 4, "\xff\xff\xff\xff");
  std::ofstream(bag, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_INPUT_ERROR(read_bag(bag, {}), "run.bag: damaged ROS 1 bag: the record at byte",
                     "declares a header of 4294967295 bytes");
}

TEST(Ros1Bag, AChunkWhoseRecordRunsPastItsEndIsDamageNotACrash) {
  // The fuzzer's second finding (its input is in the corpus): librosbag read a message record
  // of an uncompressed chunk past the chunk's end (SEGV in readHeaderFromBuffer).
  const std::filesystem::path bag =
      kBagData / ".." / ".." / "fuzz" / "corpus" / "ros1_bag" / "regression-segv-chunk-record.bag";
  for (const std::string pose_topic : {"", "/odom"}) {
    EXPECT_INPUT_ERROR(read_bag(bag, {.topic = "", .pose_topic = pose_topic}), "damaged ROS 1 bag");
  }
}

TEST(Ros1Bag, ACompressedChunkWhoseRecordRunsPastItsEndIsDamage) {
  // The first message declares 256 MB more data than it holds, inside its chunk before the
  // chunk is compressed: sizes and index agree, and only the decompressed records show it.
  // librosbag took such a bz2 or lz4 chunk as it came.
  for (const std::string compression : {"bz2", "lz4", "none"}) {
    SCOPED_TRACE(compression);
    const TempDir dir;
    const auto bag =
        write_bag(dir, "--encoding png --overlong-message 0 --compression " + compression);
    EXPECT_INPUT_ERROR(read_bag(bag, {}), "run.bag: damaged ROS 1 bag: the record at byte",
                       "is a chunk whose record at its byte", "runs past its end");
  }
}

// The bytes of `bag`, and the position of the data of its first record with `op` (its
// header's "op=" field, 1 byte), after the data's 4-byte length.
std::pair<std::string, std::size_t> first_record_data(const std::filesystem::path& bag, char op) {
  std::ifstream in(bag, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t at = 13;  // "#ROSBAG V2.0\n"
  const auto u32 = [&bytes](std::size_t i) {
    std::uint32_t value = 0;
    for (int b = 3; b >= 0; --b) value = value << 8 | static_cast<unsigned char>(bytes[i + b]);
    return value;
  };
  while (at + 4 <= bytes.size()) {
    const std::uint32_t header = u32(at);
    const bool wanted =
        bytes.substr(at + 4, header).find(std::string("op=") + op) != std::string::npos;
    const std::size_t data = at + 4 + header + 4;
    if (wanted) return {bytes, data};
    at = data + u32(data - 4);
  }
  ADD_FAILURE() << "no record with op " << int(op);
  return {bytes, 0};
}

TEST(Ros1Bag, ACompressedChunkThatDoesNotDecompressToItsSizeOrAnIndexIntoNoRecordIsDamage) {
  for (const std::string compression : {"bz2", "lz4"}) {
    SCOPED_TRACE(compression);
    const TempDir dir;
    const auto bag = write_bag(dir, "--encoding png --compression " + compression);
    // A byte of the compressed stream flipped: it no longer decompresses to the chunk's declared
    // size (or at all), which is said before any message is read.
    auto [bytes, chunk] = first_record_data(bag, '\x05');
    ASSERT_GT(chunk, 0u);
    bytes[chunk + 200] = static_cast<char>(bytes[chunk + 200] ^ 0x55);
    std::ofstream(bag, std::ios::binary | std::ios::trunc) << bytes;
    EXPECT_INPUT_ERROR(read_bag(bag, {}), "run.bag: damaged ROS 1 bag: the record at byte",
                       "chunk that does not decompress to the");
  }
  // An index entry (time, 8 bytes, then the message's offset in its chunk, 4) naming a byte
  // beyond the chunk: librosbag read a record there (SEGV; the input is in the fuzz corpus).
  const TempDir dir;
  const auto bag = write_bag(dir, "--encoding png --compression bz2");
  auto [bytes, index] = first_record_data(bag, '\x04');
  ASSERT_GT(index, 0u);
  bytes.replace(index + 8, 4, std::string("\x00\x00\x00\x10", 4));
  std::ofstream(bag, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_INPUT_ERROR(read_bag(bag, {}), "is an index naming byte 268435456 of its chunk",
                     "where no record starts");
}

TEST(Ros1Bag, TwoImageTopicsNeedTopicAndTheErrorNamesBoth) {
  const TempDir dir;
  const auto bag = write_bag(dir, "--second-camera");
  EXPECT_INPUT_ERROR(read_bag(bag, {}), "run.bag", "several image topics", "/camera/image_raw",
                     "/camera2/image_raw", "--topic");
  expect_route(read_bag(bag, {.topic = "/camera/image_raw", .pose_topic = ""}), Pixels::kColour,
               false);
  EXPECT_INPUT_ERROR(read_bag(bag, {.topic = "/camera3", .pose_topic = ""}), "no topic /camera3",
                     "/camera2/image_raw");
}

TEST(Ros1Bag, TopicsOfTheWrongTypeAreRefused) {
  const TempDir dir;
  const auto bag = write_bag(dir, "--poses odometry");
  EXPECT_INPUT_ERROR(read_bag(bag, {.topic = "/odom", .pose_topic = ""}), "/odom",
                     "nav_msgs/Odometry", "not sensor_msgs/Image");
  EXPECT_INPUT_ERROR(read_bag(bag, {.topic = "", .pose_topic = "/camera/image_raw"}),
                     "/camera/image_raw", "not nav_msgs/Odometry");
}

TEST(Ros1Bag, TruncatedBagSaysHowToRecoverAndReindexedKeepsTheFramesBefore) {
  const TempDir dir;
  // One message a chunk, cut in the sixth image's chunk: as a recording killed mid-write.
  const auto bag = write_bag(dir, "--poses odometry --chunk-bytes 1000 --truncate-bytes 25000");
  EXPECT_INPUT_ERROR(read_bag(bag, {}), "run.bag", "truncated", "rosbag reindex");
  const std::string reindex = "cd " + dir.path().string() + " && " + OMNINAV_DEBIAN_PYTHON +
                              " /usr/bin/rosbag reindex run.bag > /dev/null";
  ASSERT_EQ(std::system(reindex.c_str()), 0);
  const std::vector<Frame> frames = read_bag(bag, {.topic = "", .pose_topic = "/odom"});
  ASSERT_EQ(frames.size(), 5u);  // the images whose chunks are whole
  // The poses up to the fourth frame; the fifth's pose was lost, and is not extrapolated.
  std::vector<Frame> posed(frames.begin(), frames.begin() + 4);
  expect_route(posed, Pixels::kColour, true, 4);
  EXPECT_FALSE(frames[4].truth.has_value());
}

TEST(Ros1Bag, BayerImagesAreDemosaicedWithTheirColoursInPlace) {
  const TempDir dir;
  const std::vector<Frame> frames = read_bag(write_bag(dir, "--encoding bayer_rggb8"), {});
  const std::vector<Frame> route = testing::route_frames();
  ASSERT_EQ(frames.size(), route.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    ASSERT_EQ(frames[i].image.type(), CV_8UC3);
    // Demosaicing interpolates two of every three samples: close to the database, and much
    // closer than with red and blue swapped (a pattern read the wrong way round).
    cv::Mat swapped;
    cv::cvtColor(route[i].image, swapped, cv::COLOR_BGR2RGB);
    const double error = cv::norm(frames[i].image, route[i].image, cv::NORM_L1) /
                         static_cast<double>(route[i].image.total() * 3);
    const double swapped_error = cv::norm(frames[i].image, swapped, cv::NORM_L1) /
                                 static_cast<double>(route[i].image.total() * 3);
    EXPECT_LT(error, 8.0) << "frame " << i;                  // measured 4.8-6.2
    EXPECT_GT(swapped_error, 3.0 * error) << "frame " << i;  // measured 22-28
    // Where the mosaic sampled a colour, it is kept: red on even rows and columns, blue on odd.
    for (int row = 1; row + 1 < route[i].image.rows; ++row) {
      for (int col = 1; col + 1 < route[i].image.cols; ++col) {
        const int channel = row % 2 == 0 && col % 2 == 0 ? 2 : row % 2 == 1 && col % 2 == 1 ? 0 : 1;
        ASSERT_EQ(frames[i].image.at<cv::Vec3b>(row, col)[channel],
                  route[i].image.at<cv::Vec3b>(row, col)[channel])
            << "frame " << i << " row " << row << " col " << col;
      }
    }
  }
}

}  // namespace
}  // namespace omninav::io
