#pragma once
// One panorama made ready for the visual compass: checked, copied into one continuous 8-bit
// block (1 channel, or 3 in OpenCV's BGR order), and carrying the caches that belong to the
// image itself, so that work done on a frame is done once however many pairs it is part of:
//   - its FFT spectra for the masked cross-correlation (fft_correlation.hpp): the spectra of
//     its rows "as the first image" and "as the second image" of a pair (Labrosse 2006, Eq. 2),
//     each computed at most once, on first use. Algorithm 1 compares the current frame with the
//     reference and, on a switch, the previous frame with the current one: every frame plays
//     both roles, and these caches are the "cache keyed by frame" that makes each transform
//     happen once;
//   - the low-frequency components of its rows for the phase estimate (phase.hpp);
//   - its own amplitude A(I, I) (Labrosse 2006, Eq. 8's normaliser), per distance function;
//   - a column-major copy of its pixels for the fast distance kernel (distance.hpp).
// The pixels never change after construction. Copies share the pixels and the caches. The
// caches are filled under a mutex, so const use from several threads is safe.

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

namespace omninav::compass {

namespace detail {
struct FrameCaches;  // defined in src/frame_caches.hpp
}

class CompassFrame {
 public:
  // Throws InputError naming `source` (or "frame <index>") when `panorama` is empty or is not
  // an 8-bit 1- or 3-channel image.
  explicit CompassFrame(const cv::Mat& panorama, int index = 0, std::string source = {});

  int width() const { return image_.cols; }
  int height() const { return image_.rows; }
  int channels() const { return image_.channels(); }
  // Position of the frame in its sequence (for output and messages).
  int index() const { return index_; }
  // Where the frame came from ("frame 12" when nobody said).
  const std::string& source() const { return source_; }
  const cv::Mat& image() const { return image_; }

  // Row r, width()·channels() bytes, pixels left to right, channels interleaved.
  const std::uint8_t* row(int r) const { return image_.ptr<std::uint8_t>(r); }

  // The pixels column-major: column c's height()·channels() bytes (rows top to bottom, channels
  // interleaved) start at c·height()·channels(). Made on first use and kept.
  const std::uint8_t* column_major() const;

  // Whether two frames can be compared: same width, height and channel count.
  bool same_shape(const CompassFrame& other) const;
  // "180x50x3"
  std::string shape() const;

  detail::FrameCaches& caches() const { return *caches_; }

 private:
  cv::Mat image_;  // continuous, CV_8UC1 or CV_8UC3
  int index_ = 0;
  std::string source_;
  std::shared_ptr<detail::FrameCaches> caches_;
};

// Throws InputError naming both frames unless they have the same shape.
void require_same_shape(const CompassFrame& first, const CompassFrame& second);

}  // namespace omninav::compass
