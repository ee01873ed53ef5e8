#pragma once
// A video file read with cv::VideoCapture (docs/design.md, Data formats: Input sequences). Capture
// times come from the frame rate the container declares; a video has no poses.

#include <filesystem>
#include <opencv2/videoio.hpp>

#include "omninav/io/image_file.hpp"
#include "omninav/io/sequence.hpp"

namespace omninav::io {

class VideoSequence : public SequenceReader {
 public:
  // Throws InputError naming `file` when it cannot be opened or yields no frame at all.
  explicit VideoSequence(const std::filesystem::path& file);

  // Frame i has time_s = i / fps when the container declares fps > 0, and source
  // "<file>#frame <i>".
  std::optional<Frame> next() override;
  // What the container declares; 0 when it does not know.
  std::size_t size() const override { return declared_frames_; }
  std::string describe() const override;
  bool is_video() const override { return true; }

  // The frame rate the container declares, if any.
  std::optional<double> fps() const { return fps_; }

 private:
  std::filesystem::path file_;
  cv::VideoCapture capture_;
  std::optional<double> fps_;
  std::size_t declared_frames_ = 0;
  // The next frame, read ahead so that the end is known before it is reached and an unreadable
  // file fails when opened rather than on the first next().
  cv::Mat pending_;
  int next_index_ = 0;
  ImageSizeCheck size_check_;
};

}  // namespace omninav::io
