#include "omninav/core/image_size.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>

#include "omninav/core/errors.hpp"

namespace omninav {
namespace {

// The header is read here, by hand, because OpenCV offers no way to: its decoders read the
// header and then the pixels in one imread(), the decoder classes are not public API, and its
// own limit (OPENCV_IO_MAX_IMAGE_PIXELS, read once per process from the environment) is 2^30
// pixels by default, a 3 GB image. PNG and JPEG are what cameras and omninav write; for the
// other formats the decoded size is checked after the fact.

// Big-endian unsigned integer of `bytes` bytes at `at`.
std::uint32_t big_endian(const std::vector<unsigned char>& data, std::size_t at, int bytes) {
  std::uint32_t value = 0;
  for (int i = 0; i < bytes; ++i) value = value << 8 | data[at + static_cast<std::size_t>(i)];
  return value;
}

std::vector<unsigned char> read_prefix(const std::filesystem::path& file, std::size_t bytes) {
  std::ifstream stream(file, std::ios::binary);
  std::vector<unsigned char> data(bytes);
  stream.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(bytes));
  data.resize(static_cast<std::size_t>(std::max<std::streamsize>(stream.gcount(), 0)));
  return data;
}

constexpr std::size_t kPngHeaderBytes = 24;

std::optional<cv::Size> png_size(const std::vector<unsigned char>& data) {
  // Signature (8 bytes), then the IHDR chunk: length (4), "IHDR", width (4), height (4).
  constexpr unsigned char kSignature[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (data.size() < kPngHeaderBytes ||
      !std::equal(std::begin(kSignature), std::end(kSignature), data.begin()) ||
      std::string(data.begin() + 12, data.begin() + 16) != "IHDR") {
    return std::nullopt;
  }
  const std::uint32_t width = big_endian(data, 16, 4), height = big_endian(data, 20, 4);
  constexpr std::uint32_t kMaxSide = 1u << 30;  // keeps the size an int
  return cv::Size(static_cast<int>(std::min(width, kMaxSide)),
                  static_cast<int>(std::min(height, kMaxSide)));
}

bool starts_as_jpeg(const std::vector<unsigned char>& data) {
  return data.size() >= 2 && data[0] == 0xFF && data[1] == 0xD8;
}

// `byte()` gives the next byte or a negative number at the end, `skip(n)` passes n bytes: the
// same parser for a file and for bytes in memory.
template <typename Byte, typename Skip>
std::optional<cv::Size> jpeg_size(Byte byte, Skip skip) {
  // Segments from the start-of-image marker: FF <marker> <length, 2 bytes, including itself>
  // <payload>, up to a start-of-frame (C0-CF but C4 DHT, C8 JPG, CC DAC), whose payload is
  // precision (1), height (2), width (2). Exif thumbnails sit inside APP1's payload, skipped.
  if (byte() != 0xFF || byte() != 0xD8) return std::nullopt;
  while (true) {
    int marker = byte();
    if (marker != 0xFF) return std::nullopt;
    while (marker == 0xFF) marker = byte();  // fill bytes
    if (marker < 0) return std::nullopt;
    if (marker == 0xD8 || marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue;
    if (marker == 0xD9 || marker == 0xDA) return std::nullopt;  // end, or scan before a frame
    const int high = byte(), low = byte();
    if (high < 0 || low < 0) return std::nullopt;
    const int length = high << 8 | low;
    if (length < 2) return std::nullopt;
    if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) {
      if (length < 7) return std::nullopt;
      byte();  // precision
      const int h1 = byte(), h0 = byte(), w1 = byte(), w0 = byte();
      if (w0 < 0) return std::nullopt;
      return cv::Size(w1 << 8 | w0, h1 << 8 | h0);
    }
    if (!skip(length - 2)) return std::nullopt;
  }
}

}  // namespace

void check_image_pixels(const cv::Size& size, const std::string& where) {
  if (static_cast<long long>(size.width) * size.height > kMaxImagePixels) {
    throw InputError(where + ": image is " + size_text(size) + ", more than omninav reads (" +
                     std::to_string(kMaxImagePixels / 1000000) + " megapixels at most)");
  }
}

std::optional<cv::Size> declared_image_size(const std::filesystem::path& file) {
  const std::vector<unsigned char> prefix = read_prefix(file, kPngHeaderBytes);
  if (std::optional<cv::Size> size = png_size(prefix)) return size;
  if (!starts_as_jpeg(prefix)) return std::nullopt;
  std::ifstream stream(file, std::ios::binary);
  return jpeg_size(
      [&]() -> int { return stream.get(); },
      [&](int count) { return static_cast<bool>(stream.seekg(count, std::ios::cur)); });
}

std::optional<cv::Size> declared_image_size(const std::vector<std::uint8_t>& bytes) {
  const std::vector<unsigned char> prefix(
      bytes.begin(), bytes.begin() + std::min<std::size_t>(bytes.size(), kPngHeaderBytes));
  if (std::optional<cv::Size> size = png_size(prefix)) return size;
  if (!starts_as_jpeg(prefix)) return std::nullopt;
  std::size_t at = 0;
  return jpeg_size([&]() -> int { return at < bytes.size() ? bytes[at++] : -1; },
                   [&](int count) {
                     at += static_cast<std::size_t>(count);
                     return at <= bytes.size();
                   });
}

void check_declared_image_pixels(const std::filesystem::path& file) {
  if (const std::optional<cv::Size> declared = declared_image_size(file)) {
    check_image_pixels(*declared, file.string());
  }
}

std::string size_text(const cv::Size& size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height) + " px";
}

}  // namespace omninav
