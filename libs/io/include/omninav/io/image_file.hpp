#pragma once
// Reading image files the way every reader of io does, and the one-size-per-sequence check.

#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

namespace omninav::io {

// Reads `file` as 8-bit BGR (cv::IMREAD_COLOR, so grey files come back as three equal
// channels: one pixel type for every sequence, whatever its source). Throws InputError naming
// the file when it is missing, unreadable or not a decodable image.
cv::Mat read_image(const std::filesystem::path& file);

// Remembers the size of the first image of a sequence and rejects any other size: a sequence
// of panoramas of mixed sizes cannot be compared column by column.
class ImageSizeCheck {
 public:
  // Throws InputError naming `source` and both sizes when `image` differs from the first one.
  void check(const cv::Mat& image, const std::string& source);

 private:
  std::optional<cv::Size> first_size_;
  std::string first_source_;
};

}  // namespace omninav::io
