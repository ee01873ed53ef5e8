#pragma once
// A live camera as a sequence (`--input camera:0`): a V4L2 device read through cv::VideoCapture
// by a grabbing thread into a bounded queue, so that the camera is read at its own rate while
// the frames are processed at theirs. Nothing is dropped silently: when the processing falls
// behind and the queue is full, the oldest waiting frame is dropped and counted, and the count
// is logged at the end and given by notes() (explore keeps it in the map's run). Frame indices
// are the capture's own, so a dropped frame leaves a gap. Ctrl-C (SIGINT) while a camera is
// open ends the sequence at the next frame: the command then writes its map or table up to the
// last frame it processed; a second Ctrl-C kills the program as usual.
//
// A video file stands in for a camera (`camera:clip.avi`, for tests and replays): the same
// thread and queue, the frames delivered at the rate the container's timestamps say.
//
// No decision depends on the wall clock: frame times come from the capture's timestamps (a
// device's buffer times, a file's positions), relative to the first frame, for reports only.
// Which frames a live camera drops depends on the speed of the processing, as it must; given
// the frames, every result is the same.

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <memory>
#include <mutex>
#include <opencv2/videoio.hpp>
#include <optional>
#include <string>
#include <thread>

#include "omninav/io/image_file.hpp"
#include "omninav/io/sequence.hpp"

namespace omninav::io {

// The prefix of an input that names a camera: "camera:0", "camera:/dev/video2", "camera:f.avi".
inline constexpr const char* kCameraPrefix = "camera:";

// What follows "camera:" in `input`, or nothing when `input` does not name a camera.
std::optional<std::string> camera_device(const std::string& input);

struct CameraOptions {
  // Frames captured and waiting to be processed; when full, the oldest is dropped and counted.
  std::size_t queue_frames = 32;
  // A video file standing in for a camera delivers its frames at the pace of its timestamps,
  // as a camera would; false delivers them as fast as they are read (tests).
  bool pace_file = true;
};

class CameraSequence : public SequenceReader {
 public:
  // `device`: a V4L2 device number ("0") or path ("/dev/video0"), or a video file standing in
  // for a camera. Reads the first frame before returning; throws InputError naming the camera
  // when it cannot be opened or gives no frame. Catches SIGINT while it lives (see above).
  explicit CameraSequence(const std::string& device, CameraOptions options = {});
  ~CameraSequence() override;
  CameraSequence(const CameraSequence&) = delete;
  CameraSequence& operator=(const CameraSequence&) = delete;

  // The next frame as it comes (waiting for the camera), or nothing once the capture has ended
  // (a file's last frame, a device that stops delivering) or Ctrl-C was pressed. Frame i's
  // source is "<file>#frame i" for a file (as VideoSequence names it), "camera <device>#frame i"
  // for a device.
  std::optional<Frame> next() override;
  // A file's declared frame count; 0 for a device (unknown).
  std::size_t size() const override { return declared_frames_; }
  std::string describe() const override;
  std::string notes() const override;
  bool is_video() const override { return true; }

  std::size_t delivered_frames() const;
  // Frames dropped because the queue was full.
  std::size_t dropped_frames() const;
  bool interrupted() const;

  // Waits until the capture has ended (a file's end or a device's, or Ctrl-C); the frames still
  // queued can then be read. For tests that need a full queue.
  void wait_for_capture_end();

 private:
  struct Captured {
    int index = 0;
    cv::Mat image;
    std::optional<double> time_s;
  };
  std::optional<double> capture_time_s();
  void push(Captured captured);
  void grab_loop();
  // Logs, once, how the sequence ended and what it dropped.
  void report_end();

  std::string device_;
  bool is_file_ = false;
  std::string name_;  // "camera 0", or the file
  CameraOptions options_;
  cv::VideoCapture capture_;
  std::optional<double> fps_;
  std::size_t declared_frames_ = 0;
  cv::Size first_size_;  // describe() must not ask the capture, which the grabber is using
  std::optional<double> first_time_ms_;
  int next_capture_index_ = 0;
  ImageSizeCheck size_check_;

  mutable std::mutex mutex_;
  std::condition_variable frame_ready_;  // the grabber to next()
  std::condition_variable stop_;         // the destructor to a pacing grabber
  std::deque<Captured> queue_;
  bool capture_ended_ = false;
  bool stopping_ = false;
  bool interrupted_ = false;
  bool device_lost_ = false;  // a device's read failed before anyone stopped it
  bool reported_ = false;
  std::size_t dropped_ = 0;
  std::size_t delivered_ = 0;
  std::size_t unprocessed_ = 0;  // queued when Ctrl-C stopped the sequence
  std::thread grabber_;
  struct SignalGuard;
  std::unique_ptr<SignalGuard> signal_guard_;
};

}  // namespace omninav::io
