#include "omninav/compass/resample.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"

namespace omninav::compass {

cv::Mat resample_columns(const cv::Mat& panorama, int width_px) {
  require_panorama(panorama, "panorama to resample");
  if (width_px < 1) throw UsageError("cannot resample a panorama to fewer than 1 column");
  const int in_width = panorama.cols;
  if (in_width == width_px) return panorama.clone();
  const int channels = panorama.channels();
  const double ratio = static_cast<double>(in_width) / width_px;
  const double half_width = std::max(1.0, ratio);  // tent half-width, input columns

  // Per output column: the input columns and their normalised tent weights.
  struct Tap {
    int column;
    double weight;
  };
  std::vector<std::vector<Tap>> taps(static_cast<std::size_t>(width_px));
  for (int c = 0; c < width_px; ++c) {
    const double centre = c * ratio;
    const int first = static_cast<int>(std::ceil(centre - half_width));
    const int last = static_cast<int>(std::floor(centre + half_width));
    double total = 0.0;
    auto& column_taps = taps[static_cast<std::size_t>(c)];
    for (int k = first; k <= last; ++k) {
      const double weight = 1.0 - std::abs(k - centre) / half_width;
      if (weight <= 0.0) continue;
      const int wrapped = ((k % in_width) + in_width) % in_width;
      column_taps.push_back({wrapped, weight});
      total += weight;
    }
    for (Tap& tap : column_taps) tap.weight /= total;
  }

  cv::Mat result(panorama.rows, width_px, panorama.type());
  std::vector<double> sums(static_cast<std::size_t>(channels));
  for (int r = 0; r < panorama.rows; ++r) {
    const std::uint8_t* in = panorama.ptr<std::uint8_t>(r);
    std::uint8_t* out = result.ptr<std::uint8_t>(r);
    for (int c = 0; c < width_px; ++c) {
      std::fill(sums.begin(), sums.end(), 0.0);
      for (const Tap& tap : taps[static_cast<std::size_t>(c)]) {
        for (int l = 0; l < channels; ++l) {
          sums[static_cast<std::size_t>(l)] += tap.weight * in[tap.column * channels + l];
        }
      }
      for (int l = 0; l < channels; ++l) {
        out[c * channels + l] = static_cast<std::uint8_t>(
            std::clamp(std::lround(sums[static_cast<std::size_t>(l)]), 0L, 255L));
      }
    }
  }
  return result;
}

}  // namespace omninav::compass
