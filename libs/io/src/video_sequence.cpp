#include "omninav/io/video_sequence.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/io/image_file.hpp"
#include "quiet_stderr.hpp"

namespace omninav::io {

VideoSequence::VideoSequence(const std::filesystem::path& file) : file_(file) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) {
    throw InputError(file.string() + ": " + unreadable_file_reason(file, "video file"));
  }
  bool opened = false;
  {
    const QuietStderr quiet;  // FFmpeg's, GStreamer's and OpenCV's lines: ours says it
    opened = capture_.open(file.string());
  }
  // The size the stream declares, before a frame of it is decoded (ImageSizeCheck checks the
  // decoded frames too).
  const double width = opened ? capture_.get(cv::CAP_PROP_FRAME_WIDTH) : 0.0;
  const double height = opened ? capture_.get(cv::CAP_PROP_FRAME_HEIGHT) : 0.0;
  if (std::isfinite(width) && std::isfinite(height) && width * height > kMaxImagePixels) {
    check_image_pixels(
        cv::Size(static_cast<int>(std::min(width, 1e9)), static_cast<int>(std::min(height, 1e9))),
        file.string());
  }
  if (opened) {
    const QuietStderr quiet;
    opened = capture_.read(pending_) && !pending_.empty();
  }
  if (!opened) {
    throw InputError(file.string() +
                     ": cannot read as a video (unknown format or codec, or no frames)");
  }
  const double fps = capture_.get(cv::CAP_PROP_FPS);
  if (std::isfinite(fps) && fps > 0.0) fps_ = fps;
  // Containers may not know their length (0 or negative); the frames read then decide.
  const double count = capture_.get(cv::CAP_PROP_FRAME_COUNT);
  if (std::isfinite(count) && count > 0.0) declared_frames_ = static_cast<std::size_t>(count);
}

std::optional<Frame> VideoSequence::next() {
  if (pending_.empty()) return std::nullopt;
  Frame frame;
  frame.index = next_index_;
  frame.image = pending_;
  frame.source = file_.string() + "#frame " + std::to_string(next_index_);
  if (fps_) frame.time_s = next_index_ / *fps_;
  size_check_.check(frame.image, frame.source);
  ++next_index_;

  // A fresh Mat each time: the frame handed out must not be overwritten by the next read.
  pending_ = cv::Mat();
  {
    const QuietStderr quiet;
    if (!capture_.read(pending_)) pending_ = cv::Mat();
  }
  if (pending_.empty() && static_cast<std::size_t>(next_index_) < declared_frames_) {
    log_warning(file_.string() + ": ended after " + std::to_string(next_index_) +
                " frames, but its container declares " + std::to_string(declared_frames_));
  }
  return frame;
}

std::string VideoSequence::describe() const {
  std::ostringstream text;
  text << "video " << file_.string() << " (";
  if (declared_frames_ > 0) {
    text << declared_frames_ << " frames";
  } else {
    text << "unknown length";
  }
  if (fps_) text << " at " << *fps_ << " fps";
  text << ", no poses)";
  return text.str();
}

}  // namespace omninav::io
