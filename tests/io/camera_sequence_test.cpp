#include "omninav/io/camera_sequence.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <opencv2/videoio.hpp>

#include "io_test_support.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/io/panorama_input.hpp"
#include "omninav/io/video_sequence.hpp"

namespace omninav::io {
namespace {

using testing::TempDir;

constexpr double kFps = 10.0;
constexpr int kFrames = 6;
const cv::Size kVideoSize{64, 16};

// Frame i is a flat grey of level 20 + 40 i, which MJPEG keeps within a few levels.
bool write_test_video(const std::filesystem::path& file) {
  cv::VideoWriter writer(file.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), kFps,
                         kVideoSize);
  if (!writer.isOpened()) return false;
  for (int i = 0; i < kFrames; ++i) {
    writer.write(cv::Mat(kVideoSize, CV_8UC3, cv::Scalar::all(20 + 40 * i)));
  }
  return true;
}

constexpr const char* kNoWriter = "cv::VideoWriter cannot write MJPG in AVI on this build";
constexpr CameraOptions kUnpaced{.queue_frames = 32, .pace_file = false};

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(CameraDevice, OnlyTheCameraPrefixNamesACamera) {
  EXPECT_EQ(camera_device("camera:0"), "0");
  EXPECT_EQ(camera_device("camera:/dev/video2"), "/dev/video2");
  EXPECT_EQ(camera_device("camera:"), "");
  EXPECT_FALSE(camera_device("clip.avi"));
  EXPECT_FALSE(camera_device("images/camera:0"));
}

TEST(CameraSequence, AVideoStandingInGivesTheVideosFramesPixelForPixel) {
  const TempDir dir;
  const std::filesystem::path file = dir / "clip.avi";
  if (!write_test_video(file)) GTEST_SKIP() << kNoWriter;

  VideoSequence video(file);
  const std::vector<Frame> expected = read_all(video);
  ASSERT_EQ(expected.size(), static_cast<std::size_t>(kFrames));
  CameraSequence camera(file.string(), kUnpaced);
  EXPECT_EQ(camera.size(), static_cast<std::size_t>(kFrames));
  const std::vector<Frame> frames = read_all(camera);
  ASSERT_EQ(frames.size(), expected.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].index, expected[i].index);
    EXPECT_EQ(frames[i].source, expected[i].source);
    ASSERT_TRUE(frames[i].time_s) << "the capture's timestamp of frame " << i;
    EXPECT_NEAR(*frames[i].time_s, i / kFps, 1e-6) << "frame " << i;
    EXPECT_EQ(cv::norm(frames[i].image, expected[i].image, cv::NORM_INF), 0.0) << "frame " << i;
  }
  EXPECT_EQ(camera.dropped_frames(), 0u);
  EXPECT_FALSE(camera.interrupted());
  EXPECT_TRUE(contains(camera.notes(), "6 frames processed; 0 frames dropped")) << camera.notes();
}

TEST(CameraSequence, AFullQueueDropsTheOldestFramesAndCountsThem) {
  const TempDir dir;
  const std::filesystem::path file = dir / "clip.avi";
  if (!write_test_video(file)) GTEST_SKIP() << kNoWriter;

  // Nothing is processed until the capture has ended: a queue of 2 keeps the last 2 frames.
  CameraSequence camera(file.string(), {.queue_frames = 2, .pace_file = false});
  camera.wait_for_capture_end();
  const std::vector<Frame> frames = read_all(camera);
  ASSERT_EQ(frames.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    const int index = kFrames - 2 + i;
    EXPECT_EQ(frames[i].index, index) << "the capture's own index: a gap shows the dropped ones";
    EXPECT_NEAR(cv::mean(frames[i].image)[0], 20 + 40 * index, 4.0);
    ASSERT_TRUE(frames[i].time_s);
    EXPECT_NEAR(*frames[i].time_s, index / kFps, 1e-6);
  }
  EXPECT_EQ(camera.dropped_frames(), static_cast<std::size_t>(kFrames - 2));
  EXPECT_EQ(camera.delivered_frames(), 2u);
  EXPECT_TRUE(contains(camera.notes(), "2 frames processed; 4 frames dropped")) << camera.notes();
}

TEST(CameraSequence, CtrlCEndsTheSequenceAfterTheFrameInHandAndRestoresTheHandler) {
  const TempDir dir;
  const std::filesystem::path file = dir / "clip.avi";
  if (!write_test_video(file)) GTEST_SKIP() << kNoWriter;

  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  struct sigaction before {};
  ASSERT_EQ(::sigaction(SIGINT, &ignore, &before), 0);
  {
    CameraSequence camera(file.string());  // paced: 0.1 s a frame, as a camera would
    std::optional<Frame> first = camera.next();
    ASSERT_TRUE(first);
    EXPECT_EQ(first->index, 0);
    ASSERT_EQ(std::raise(SIGINT), 0);
    EXPECT_FALSE(camera.next()) << "Ctrl-C ends the sequence";
    EXPECT_FALSE(camera.next());
    EXPECT_TRUE(camera.interrupted());
    EXPECT_EQ(camera.delivered_frames(), 1u);
    EXPECT_TRUE(contains(camera.notes(), "1 frame processed, stopped by Ctrl-C")) << camera.notes();
  }
  struct sigaction after {};
  ASSERT_EQ(::sigaction(SIGINT, &before, &after), 0);
  EXPECT_EQ(after.sa_handler, SIG_IGN) << "the handler in place before the camera is back";
}

TEST(CameraSequence, AMissingDeviceIsAnInputErrorNamingIt) {
  EXPECT_INPUT_ERROR(CameraSequence{"97"}, "camera:97", "V4L2 device 97");
  EXPECT_INPUT_ERROR(CameraSequence{"/dev/no-such-video"}, "camera:/dev/no-such-video");
  EXPECT_THROW(CameraSequence{""}, UsageError);
}

TEST(CameraSequence, AMissingVideoIsAMissingFileAndANegativeNumberNoCamera) {
  // Not a V4L2 problem: a name that is neither a number nor /dev/... is a video file.
  EXPECT_INPUT_ERROR(CameraSequence{"missing.avi"}, "camera:missing.avi", "no such video file");
  EXPECT_THROW(CameraSequence{"-1"}, UsageError);
  EXPECT_THROW(CameraSequence{"123456789012"}, UsageError);  // not thrown by std::stoi
}

TEST(CameraSequence, PanoramaInputOpensACameraFromItsName) {
  const TempDir dir;
  const std::filesystem::path file = dir / "clip.avi";
  if (!write_test_video(file)) GTEST_SKIP() << kNoWriter;
  PanoramaInput input("camera:" + file.string(), [] { return omni::UnwrapParams{}; }, {});
  EXPECT_TRUE(contains(input.describe(), "standing in for a camera")) << input.describe();
  std::size_t frames = 0;
  while (input.next()) ++frames;
  EXPECT_EQ(frames, static_cast<std::size_t>(kFrames));
  EXPECT_TRUE(contains(input.notes(), "6 frames processed")) << input.notes();
}

}  // namespace
}  // namespace omninav::io
