#include "omninav/io/video_sequence.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <opencv2/videoio.hpp>

#include "io_test_support.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::io {
namespace {

using testing::TempDir;
using testing::write_text;

constexpr double kFps = 10.0;
constexpr int kFrames = 6;
const cv::Size kVideoSize{64, 16};

// Frame i is a flat grey of level 20 + 40 i: MJPEG keeps flat areas within a few levels, so
// the level still tells the frames apart after compression.
cv::Mat flat_frame(int index) {
  return cv::Mat(kVideoSize, CV_8UC3, cv::Scalar::all(20 + 40 * index));
}

// Writes kFrames flat frames as MJPEG in AVI (OpenCV's built-in writer, so it exists on every
// build); false when even that cannot be opened.
bool write_test_video(const std::filesystem::path& file) {
  cv::VideoWriter writer(file.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), kFps,
                         kVideoSize);
  if (!writer.isOpened()) return false;
  for (int i = 0; i < kFrames; ++i) writer.write(flat_frame(i));
  return true;
}

constexpr const char* kNoWriter = "cv::VideoWriter cannot write MJPG in AVI on this build";

TEST(VideoSequence, RoundTripKeepsCountOrderTimeAndContent) {
  const TempDir dir;
  const std::filesystem::path file = dir / "clip.avi";
  if (!write_test_video(file)) GTEST_SKIP() << kNoWriter;

  VideoSequence sequence(file);
  EXPECT_EQ(sequence.size(), static_cast<std::size_t>(kFrames));
  ASSERT_TRUE(sequence.fps());
  EXPECT_DOUBLE_EQ(*sequence.fps(), kFps);
  for (int i = 0; i < kFrames; ++i) {
    std::optional<Frame> frame = sequence.next();
    ASSERT_TRUE(frame) << "frame " << i;
    EXPECT_EQ(frame->index, i);
    ASSERT_TRUE(frame->time_s);
    EXPECT_DOUBLE_EQ(*frame->time_s, i / kFps);
    EXPECT_EQ(frame->source, file.string() + "#frame " + std::to_string(i));
    EXPECT_FALSE(frame->truth);
    EXPECT_EQ(frame->image.size(), kVideoSize);
    EXPECT_EQ(frame->image.type(), CV_8UC3);
    // Lossy codec: the mean level within 4 of what was written (levels are 40 apart).
    EXPECT_NEAR(cv::mean(frame->image)[0], 20 + 40 * i, 4.0) << "frame " << i;
  }
  EXPECT_FALSE(sequence.next());
}

TEST(VideoSequence, FramesHandedOutAreNotOverwritten) {
  const TempDir dir;
  const std::filesystem::path file = dir / "clip.avi";
  if (!write_test_video(file)) GTEST_SKIP() << kNoWriter;
  VideoSequence sequence(file);
  const std::vector<Frame> frames = read_all(sequence);
  ASSERT_EQ(frames.size(), static_cast<std::size_t>(kFrames));
  EXPECT_NEAR(cv::mean(frames.front().image)[0], 20.0, 4.0);
  EXPECT_NEAR(cv::mean(frames.back().image)[0], 20 + 40 * (kFrames - 1), 4.0);
}

TEST(VideoSequence, UnreadableFileIsInputErrorNamingIt) {
  const TempDir dir;
  const std::filesystem::path file = dir / "broken.mp4";
  write_text(file, "these bytes are no video");
  EXPECT_INPUT_ERROR(VideoSequence{file}, file.string());
}

TEST(VideoSequence, ABadVideoLeavesStandardErrorToOurMessage) {
  const TempDir dir;
  const std::filesystem::path file = dir / "bad.mp4";
  write_text(file, std::string(3000, 'Z'));
  ::testing::internal::CaptureStderr();
  EXPECT_THROW(VideoSequence{file}, InputError);
  // FFmpeg, GStreamer and OpenCV printed 8 lines here before the error line of omninav.
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(VideoSequence, AFifoIsNamedAsSuch) {
  const TempDir dir;
  const std::filesystem::path fifo = dir / "pipe.avi";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    VideoSequence{fifo};
    ADD_FAILURE() << "a FIFO was read as a video";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), fifo.string() + ": is a FIFO, not a video file");
  }
}

TEST(VideoSequence, MissingFileIsInputErrorNamingIt) {
  const TempDir dir;
  EXPECT_INPUT_ERROR(VideoSequence{dir / "absent.avi"}, (dir / "absent.avi").string());
}

}  // namespace
}  // namespace omninav::io
