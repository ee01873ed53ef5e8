// ROS 1 bags written by Debian's python3-rosbag (tests/io/bags/write_ros1_bag.py) from the
// rendered route database, read back frame for frame.

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "bag_test_support.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/io/panorama_input.hpp"

namespace omninav::io {
namespace {

using testing::expect_route;
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
