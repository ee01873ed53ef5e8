#pragma once
// Reading image files the way every reader of io does, and the one-size-per-sequence check.
// The size limit and the headers' declared sizes are core's (core/image_size.hpp), shared with
// sim's OBJ textures.

#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "omninav/core/image_size.hpp"

namespace omninav::io {

// Reads `file` as 8-bit BGR (cv::IMREAD_COLOR, so grey files come back as three equal
// channels: one pixel type for every sequence, whatever its source). Throws InputError naming
// the file when it is missing, unreadable, not a decodable image, or has more than
// kMaxImagePixels (for PNG and JPEG found from the header, before anything is decoded). Every
// image file omninav reads goes through here.
cv::Mat read_image(const std::filesystem::path& file);

// Decodes an image held in memory (a bag's CompressedImage) as read_image decodes a file: the
// size its PNG or JPEG header declares is checked against kMaxImagePixels before anything is
// decoded, and the decoded size after; OpenCV's and libpng's own lines are kept off stderr.
// `flags` as cv::imdecode's. Throws InputError "<where>: image is ..." for too many pixels;
// returns an empty Mat when the bytes are no image OpenCV decodes (the caller says what it held).
cv::Mat decode_image(const std::vector<std::uint8_t>& bytes, int flags, const std::string& where);

// Whether `file`'s extension, in any case, is one of the image formats omninav reads: png,
// jpg, jpeg, bmp, tif, tiff, ppm, pgm (the one list: folders are read by it too).
bool is_image_file_name(const std::filesystem::path& file);

// Remembers the size of the first image of a sequence and rejects any other size: a sequence
// of panoramas of mixed sizes cannot be compared column by column.
class ImageSizeCheck {
 public:
  // Throws InputError naming `source` and both sizes when `image` differs from the first one,
  // or when it has more than kMaxImagePixels (every sequence's frames pass here, whatever
  // decoded them).
  void check(const cv::Mat& image, const std::string& source);

 private:
  std::optional<cv::Size> first_size_;
  std::string first_source_;
};

}  // namespace omninav::io
