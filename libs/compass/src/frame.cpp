#include "omninav/compass/frame.hpp"

#include "frame_caches.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"

namespace omninav::compass {

CompassFrame::CompassFrame(const cv::Mat& panorama, int index, std::string source)
    : index_(index),
      source_(source.empty() ? "frame " + std::to_string(index) : std::move(source)),
      caches_(std::make_shared<detail::FrameCaches>()) {
  require_panorama(panorama, source_);
  // A private continuous copy: the caller may reuse its buffer, and the kernels read rows as
  // plain byte runs.
  image_ = panorama.clone();
}

const std::uint8_t* CompassFrame::column_major() const {
  detail::FrameCaches& caches = *caches_;
  std::call_once(caches.columns_once, [&] { cv::transpose(image_, caches.columns); });
  return caches.columns.ptr<std::uint8_t>(0);
}

bool CompassFrame::same_shape(const CompassFrame& other) const {
  return width() == other.width() && height() == other.height() && channels() == other.channels();
}

std::string CompassFrame::shape() const {
  return std::to_string(width()) + "x" + std::to_string(height()) + "x" +
         std::to_string(channels());
}

void require_same_shape(const CompassFrame& first, const CompassFrame& second) {
  if (!first.same_shape(second)) {
    throw InputError(second.source() + ": a " + second.shape() +
                     " panorama cannot be compared with " + first.source() + " (" + first.shape() +
                     "); every frame must have the same size and channels");
  }
}

}  // namespace omninav::compass
