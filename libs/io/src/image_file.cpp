#include "omninav/io/image_file.hpp"

#include <opencv2/imgcodecs.hpp>

#include "omninav/core/errors.hpp"
#include "quiet_stderr.hpp"

namespace omninav::io {
namespace {

std::string size_text(const cv::Size& size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height) + " px";
}

}  // namespace

cv::Mat read_image(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) {
    throw InputError(file.string() + ": " + unreadable_file_reason(file, "image file"));
  }
  cv::Mat image;
  try {
    const QuietStderr quiet;  // no "libpng error: ..." before our message
    image = cv::imread(file.string(), cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    // Some decoders throw on malformed headers instead of returning an empty image.
    throw InputError(file.string() + ": cannot decode image (" + e.err + ")");
  }
  if (image.empty()) {
    throw InputError(file.string() + ": cannot read image (unreadable, corrupt or not an image)");
  }
  return image;
}

void ImageSizeCheck::check(const cv::Mat& image, const std::string& source) {
  if (!first_size_) {
    first_size_ = image.size();
    first_source_ = source;
    return;
  }
  if (image.size() != *first_size_) {
    throw InputError(source + ": image is " + size_text(image.size()) +
                     ", but the sequence's first image (" + first_source_ + ") is " +
                     size_text(*first_size_));
  }
}

}  // namespace omninav::io
