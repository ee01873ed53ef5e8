#include "omninav/io/image_file.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "io_test_support.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::io {
namespace {

using testing::make_image;
using testing::TempDir;

// PNG's chunk checksum (CRC-32 of ISO 3309, as in the PNG specification's annex).
std::uint32_t png_crc(const unsigned char* bytes, std::size_t size) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= bytes[i];
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xFFFFFFFFu;
}

void put_big_endian(std::vector<unsigned char>& bytes, std::size_t at, std::uint32_t value,
                    int count) {
  for (int i = count - 1; i >= 0; --i, value >>= 8)
    bytes[at + static_cast<std::size_t>(i)] = value & 0xFF;
}

// A small PNG whose header (IHDR, with a valid checksum) declares `declared` pixels.
std::vector<unsigned char> png_declaring(cv::Size declared) {
  std::vector<unsigned char> png;
  cv::imencode(".png", make_image(0), png);
  put_big_endian(png, 16, static_cast<std::uint32_t>(declared.width), 4);
  put_big_endian(png, 20, static_cast<std::uint32_t>(declared.height), 4);
  put_big_endian(png, 29, png_crc(&png[12], 17), 4);  // over "IHDR" and its 13 bytes
  return png;
}

// A small JPEG whose start-of-frame declares `declared` pixels.
std::vector<unsigned char> jpeg_declaring(cv::Size declared) {
  std::vector<unsigned char> jpeg;
  cv::imencode(".jpg", make_image(0), jpeg);
  for (std::size_t i = 2; i + 9 < jpeg.size(); ++i) {
    if (jpeg[i] == 0xFF && jpeg[i + 1] == 0xC0) {
      put_big_endian(jpeg, i + 5, static_cast<std::uint32_t>(declared.height), 2);
      put_big_endian(jpeg, i + 7, static_cast<std::uint32_t>(declared.width), 2);
      return jpeg;
    }
  }
  ADD_FAILURE() << "no baseline start-of-frame in OpenCV's JPEG";
  return jpeg;
}

void write_bytes(const std::filesystem::path& file, const std::vector<unsigned char>& bytes) {
  testing::write_text(file, std::string(bytes.begin(), bytes.end()));
}

TEST(ImageFile, DeclaredSizeComesFromThePngAndJpegHeaders) {
  const TempDir dir;
  const cv::Mat image = make_image(3, {37, 11});
  ASSERT_TRUE(cv::imwrite((dir / "a.png").string(), image));
  ASSERT_TRUE(cv::imwrite((dir / "a.jpg").string(), image));
  ASSERT_TRUE(cv::imwrite((dir / "a.bmp").string(), image));
  EXPECT_EQ(declared_image_size(dir / "a.png"), cv::Size(37, 11));
  EXPECT_EQ(declared_image_size(dir / "a.jpg"), cv::Size(37, 11));
  EXPECT_EQ(declared_image_size(dir / "a.bmp"), std::nullopt);  // decoded, then checked
  testing::write_text(dir / "short.png", "\x89PNG\r\n");
  EXPECT_EQ(declared_image_size(dir / "short.png"), std::nullopt);
  EXPECT_EQ(read_image(dir / "a.png").size(), cv::Size(37, 11));
}

TEST(ImageFile, AnImageDeclaringTooManyPixelsIsRefusedBeforeDecoding) {
  const TempDir dir;
  // 20000 x 20000 would be 1.2 GB decoded; the header alone says so.
  write_bytes(dir / "huge.png", png_declaring({20000, 20000}));
  EXPECT_INPUT_ERROR(read_image(dir / "huge.png"), (dir / "huge.png").string(), "20000x20000 px",
                     "67 megapixels at most");
  write_bytes(dir / "huge.jpg", jpeg_declaring({30000, 30000}));
  EXPECT_INPUT_ERROR(read_image(dir / "huge.jpg"), (dir / "huge.jpg").string(), "30000x30000 px");
  // At the limit, the header check lets the image through to the decoder.
  write_bytes(dir / "limit.png", png_declaring({8192, 8192}));
  EXPECT_EQ(declared_image_size(dir / "limit.png"), cv::Size(8192, 8192));
}

}  // namespace
}  // namespace omninav::io
