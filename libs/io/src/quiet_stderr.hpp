#pragma once
// OpenCV's decoders and video back ends (libpng, FFmpeg, GStreamer, OpenCV's own log) print
// their lines on standard error, 1 to 14 of them before ours for one bad file. While a
// QuietStderr lives, standard error goes to /dev/null; the one-line error naming the file
// that our caller throws afterwards says what failed.

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>

namespace omninav::io {

class QuietStderr {
 public:
  QuietStderr() {
    std::fflush(stderr);
    saved_ = ::dup(2);
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved_ >= 0 && null >= 0) ::dup2(null, 2);
    if (null >= 0) ::close(null);
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;
  ~QuietStderr() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    ::dup2(saved_, 2);
    ::close(saved_);
  }

 private:
  int saved_ = -1;
};

}  // namespace omninav::io
