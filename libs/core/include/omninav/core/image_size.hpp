#pragma once
// The one limit on the size of an image omninav decodes, and the sizes PNG and JPEG declare in
// their headers, read before anything is decoded: here, below every library that reads image
// files (io's sequences and bags, sim's OBJ textures), so that they share one check.

#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace omninav {

// The most pixels an input image may have: 8192 x 8192 (192 MB as 8-bit BGR), far beyond any
// omnidirectional camera's frame or a world's texture. More is a damaged or hostile file (a
// 1 MB PNG can declare 20000 x 20000 pixels, 1.2 GB once decoded).
inline constexpr long long kMaxImagePixels = 8192LL * 8192LL;

// InputError "<where>: image is <w>x<h> px, more than omninav reads ..." beyond kMaxImagePixels:
// for sizes declared before decoding (a header, a raw image's message, a video's stream) and
// decoded after.
void check_image_pixels(const cv::Size& size, const std::string& where);

// The size a PNG or JPEG declares in its header (PNG's IHDR, JPEG's start-of-frame), of a file
// or of bytes in memory, or nothing for other formats and for headers too short or malformed to
// say.
std::optional<cv::Size> declared_image_size(const std::filesystem::path& file);
std::optional<cv::Size> declared_image_size(const std::vector<std::uint8_t>& bytes);

// check_image_pixels of the size `file`'s header declares, if it declares one (named by the
// file): what an image file costs decoded, known before decoding it.
void check_declared_image_pixels(const std::filesystem::path& file);

// "<width>x<height> px", as messages about image sizes say it.
std::string size_text(const cv::Size& size);

}  // namespace omninav
