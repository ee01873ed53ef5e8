#include "omninav/io/camera_sequence.hpp"

#include <atomic>
#include <cmath>
#include <csignal>
#include <sstream>

#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "quiet_stderr.hpp"

namespace omninav::io {
namespace {

// Set by the SIGINT handler, read by next() and the grabber. A lock-free atomic is what a
// handler may set and other threads may read.
std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void on_interrupt(int) {
  g_interrupted.store(true);
}

bool all_digits(const std::string& text) {
  return !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
}

std::string plural(std::size_t count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

}  // namespace

// Catches SIGINT while a camera is open, and puts back what was there before. SA_RESETHAND: a
// second Ctrl-C finds the default action again and ends the program.
struct CameraSequence::SignalGuard {
  struct sigaction previous {};
  SignalGuard() {
    g_interrupted.store(false);
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND | SA_RESTART;
    sigaction(SIGINT, &action, &previous);
  }
  ~SignalGuard() { sigaction(SIGINT, &previous, nullptr); }
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;
};

std::optional<std::string> camera_device(const std::string& input) {
  const std::string prefix = kCameraPrefix;
  if (input.rfind(prefix, 0) != 0) return std::nullopt;
  return input.substr(prefix.size());
}

CameraSequence::CameraSequence(const std::string& device, CameraOptions options)
    : device_(device), options_(options) {
  if (device.empty()) {
    throw UsageError(std::string(kCameraPrefix) +
                     " names no camera: give a device number (camera:0), a device "
                     "(camera:/dev/video0) or a video file standing in for one");
  }
  if (options_.queue_frames == 0) throw UsageError("a camera's queue must hold a frame at least");
  // A number is a V4L2 device index, /dev/... a device, anything else a video file.
  const bool number = all_digits(device);
  if (number && device.size() > 4) {
    throw UsageError(std::string(kCameraPrefix) + device + ": no such camera number (0 to 9999)");
  }
  if (!number && device.rfind("/dev/", 0) != 0) {
    if (device.front() == '-' && device.find_first_not_of("-+0123456789") == std::string::npos) {
      throw UsageError(std::string(kCameraPrefix) + device +
                       ": not a camera (a device number is 0, 1, ...; or give /dev/videoN or a "
                       "video file)");
    }
    std::error_code error;
    if (!std::filesystem::is_regular_file(device, error)) {
      throw InputError(std::string(kCameraPrefix) + device + ": " +
                       unreadable_file_reason(device, "video file"));
    }
  }
  is_file_ = !number && device.rfind("/dev/", 0) != 0;
  name_ = is_file_ ? device : "camera " + device;
  bool opened = false;
  cv::Mat first;
  {
    const QuietStderr quiet;  // FFmpeg's, GStreamer's and V4L2's lines: ours says it
    if (is_file_) {
      opened = capture_.open(device);
    } else if (all_digits(device)) {
      opened = capture_.open(std::stoi(device), cv::CAP_V4L2);
    } else {
      opened = capture_.open(device, cv::CAP_V4L2);
    }
    opened = opened && capture_.read(first) && !first.empty();
  }
  if (!opened) {
    throw InputError(
        std::string(kCameraPrefix) + device +
        (is_file_ ? ": cannot read as a video (unknown format or codec, or no frames)"
                  : ": cannot read a frame from V4L2 device " + device +
                        " (no such camera, busy, or no permission; `v4l2-ctl --list-devices` "
                        "lists them)"));
  }
  const double fps = capture_.get(cv::CAP_PROP_FPS);
  if (std::isfinite(fps) && fps > 0.0) fps_ = fps;
  if (is_file_) {
    const double count = capture_.get(cv::CAP_PROP_FRAME_COUNT);
    if (std::isfinite(count) && count > 0.0) declared_frames_ = static_cast<std::size_t>(count);
  }
  first_size_ = first.size();
  signal_guard_ = std::make_unique<SignalGuard>();
  push({next_capture_index_++, first, capture_time_s()});
  grabber_ = std::thread([this] { grab_loop(); });
}

CameraSequence::~CameraSequence() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  stop_.notify_all();
  if (grabber_.joinable()) grabber_.join();
}

std::optional<double> CameraSequence::capture_time_s() {
  const double ms = capture_.get(cv::CAP_PROP_POS_MSEC);
  if (!std::isfinite(ms) || ms < 0.0) return std::nullopt;
  if (!first_time_ms_) first_time_ms_ = ms;
  return (ms - *first_time_ms_) / 1000.0;
}

void CameraSequence::push(Captured captured) {
  {
    const std::lock_guard lock(mutex_);
    if (queue_.size() >= options_.queue_frames) {
      queue_.pop_front();
      ++dropped_;
    }
    queue_.push_back(std::move(captured));
  }
  frame_ready_.notify_all();
}

void CameraSequence::grab_loop() {
  // A file standing in for a camera delivers frame i at (its timestamp) after the first.
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    {
      const std::lock_guard lock(mutex_);
      if (stopping_ || g_interrupted.load()) break;
    }
    cv::Mat image;  // a fresh Mat each time: the queued ones must not be overwritten
    if (!capture_.read(image) || image.empty()) {
      const std::lock_guard lock(mutex_);
      // A file ends; a device that stops delivering (unplugged, failed) is worth saying.
      device_lost_ = !is_file_ && !stopping_ && !g_interrupted.load();
      break;
    }
    Captured captured{next_capture_index_++, image, capture_time_s()};
    if (is_file_ && options_.pace_file && captured.time_s) {
      std::unique_lock lock(mutex_);
      const auto due = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                   std::chrono::duration<double>(*captured.time_s));
      if (stop_.wait_until(lock, due, [this] { return stopping_; })) break;
    }
    push(std::move(captured));
  }
  {
    const std::lock_guard lock(mutex_);
    capture_ended_ = true;
  }
  frame_ready_.notify_all();
}

std::optional<Frame> CameraSequence::next() {
  std::optional<Captured> captured;
  {
    std::unique_lock lock(mutex_);
    for (;;) {
      if (g_interrupted.load() && !interrupted_) {
        interrupted_ = true;
        stopping_ = true;
        unprocessed_ = queue_.size();
        queue_.clear();
      }
      if (interrupted_) break;
      if (!queue_.empty()) {
        captured = std::move(queue_.front());
        queue_.pop_front();
        ++delivered_;
        break;
      }
      if (capture_ended_) break;
      // A signal handler cannot wake a condition variable: look at the flag every 50 ms.
      frame_ready_.wait_for(lock, std::chrono::milliseconds(50));
    }
  }
  if (!captured) {
    stop_.notify_all();
    report_end();
    return std::nullopt;
  }
  Frame frame;
  frame.index = captured->index;
  frame.image = std::move(captured->image);
  frame.time_s = captured->time_s;
  frame.source = (is_file_ ? device_ : name_) + "#frame " + std::to_string(captured->index);
  size_check_.check(frame.image, frame.source);
  return frame;
}

std::string CameraSequence::describe() const {
  std::ostringstream text;
  if (is_file_) {
    text << "video " << device_ << " standing in for a camera (";
    if (declared_frames_ > 0) text << declared_frames_ << " frames";
    if (fps_) text << (declared_frames_ > 0 ? " " : "") << "at " << *fps_ << " fps";
    text << (options_.pace_file ? ", delivered at its pace" : ", delivered as read");
  } else {
    text << name_ << " (V4L2, " << first_size_.width << "x" << first_size_.height;
    if (fps_) text << " at " << *fps_ << " fps";
  }
  text << "; a queue of " << options_.queue_frames
       << " frames, the oldest dropped and counted when full; Ctrl-C stops)";
  return text.str();
}

std::string CameraSequence::notes() const {
  const std::lock_guard lock(mutex_);
  std::ostringstream text;
  text << name_ << ": " << plural(delivered_, "frame") << " processed";
  if (interrupted_) {
    text << ", stopped by Ctrl-C";
    if (unprocessed_ > 0) text << " (" << plural(unprocessed_, "captured frame") << " left)";
  }
  if (device_lost_) text << ", then the camera stopped delivering frames";
  text << "; " << plural(dropped_, "frame") << " dropped";
  if (dropped_ > 0) {
    text << " (the processing fell behind the camera: its queue of " << options_.queue_frames
         << " frames was full)";
  }
  return text.str();
}

std::size_t CameraSequence::delivered_frames() const {
  const std::lock_guard lock(mutex_);
  return delivered_;
}

std::size_t CameraSequence::dropped_frames() const {
  const std::lock_guard lock(mutex_);
  return dropped_;
}

bool CameraSequence::interrupted() const {
  const std::lock_guard lock(mutex_);
  return interrupted_;
}

void CameraSequence::wait_for_capture_end() {
  std::unique_lock lock(mutex_);
  frame_ready_.wait(lock, [this] { return capture_ended_; });
}

void CameraSequence::report_end() {
  bool warn = false;
  {
    const std::lock_guard lock(mutex_);
    if (reported_) return;
    reported_ = true;
    warn = dropped_ > 0 || device_lost_;
  }
  if (warn) {
    log_warning(notes());
  } else {
    log_info(notes());
  }
}

}  // namespace omninav::io
