#include "omninav/io/image_file.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <opencv2/imgcodecs.hpp>
#include <string_view>
#include <vector>

#include "omninav/core/errors.hpp"
#include "quiet_stderr.hpp"

namespace omninav::io {

cv::Mat decode_image(const std::vector<std::uint8_t>& bytes, int flags, const std::string& where) {
  if (const std::optional<cv::Size> declared = declared_image_size(bytes)) {
    check_image_pixels(*declared, where);
  }
  cv::Mat image;
  try {
    const QuietStderr quiet;  // no "libpng error: ..." before our message
    image = cv::imdecode(bytes, flags);
  } catch (const cv::Exception&) {
    image = cv::Mat();  // some decoders throw on malformed headers instead of returning nothing
  }
  if (!image.empty()) check_image_pixels(image.size(), where);
  return image;
}

cv::Mat read_image(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) {
    throw InputError(file.string() + ": " + unreadable_file_reason(file, "image file"));
  }
  check_declared_image_pixels(file);
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
  check_image_pixels(image.size(), file.string());
  return image;
}

void ImageSizeCheck::check(const cv::Mat& image, const std::string& source) {
  check_image_pixels(image.size(), source);
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

bool is_image_file_name(const std::filesystem::path& file) {
  constexpr std::array<std::string_view, 8> kImageExtensions = {".png", ".jpg",  ".jpeg", ".bmp",
                                                                ".tif", ".tiff", ".ppm",  ".pgm"};
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return std::find(kImageExtensions.begin(), kImageExtensions.end(), extension) !=
         kImageExtensions.end();
}

}  // namespace omninav::io
