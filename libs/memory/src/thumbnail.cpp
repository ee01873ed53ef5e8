#include "omninav/memory/thumbnail.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "omninav/core/errors.hpp"

namespace omninav::memory {

std::vector<std::uint8_t> make_thumbnail(const cv::Mat& panorama, int width_px) {
  cv::Mat small;
  const int height =
      std::max(1, static_cast<int>(std::lround(panorama.rows * double(width_px) / panorama.cols)));
  cv::resize(panorama, small, cv::Size(width_px, height), 0, 0, cv::INTER_AREA);
  std::vector<std::uint8_t> png;
  if (!cv::imencode(".png", small, png)) throw Error("cannot encode a thumbnail as PNG");
  return png;
}

cv::Mat decode_thumbnail(const std::vector<std::uint8_t>& png, const std::string& place_name) {
  if (png.empty()) {
    throw InputError(place_name +
                     " has no stored thumbnail (explore with memory.yaml's thumbnail_width_px "
                     "above 0)");
  }
  cv::Mat thumbnail = cv::imdecode(png, cv::IMREAD_COLOR);
  if (thumbnail.empty()) throw InputError(place_name + ": its thumbnail cannot be decoded");
  return thumbnail;
}

}  // namespace omninav::memory
