// A place's thumbnail (thumbnail.hpp): stored small and decoded again.
#include "omninav/memory/thumbnail.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "grid_fixture.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::memory {
namespace {

cv::Mat rendered_panorama() {
  return testing::render_frame(CameraPose{1.2, 2.3, 1.0, 0.2, 0.0, 0.0}, 0, "p").image;
}

TEST(Thumbnail, IsASmallPngCopyDecodedToTheSameSize) {
  const cv::Mat panorama = rendered_panorama();
  ASSERT_EQ(panorama.cols, 360);
  const std::vector<std::uint8_t> png = make_thumbnail(panorama, 180);
  const cv::Mat decoded = decode_thumbnail(png, "place 0");
  EXPECT_EQ(decoded.cols, 180);
  EXPECT_EQ(decoded.rows, 23);  // 45 · 180/360 rounded
  EXPECT_EQ(decoded.channels(), 3);
  // The panorama area-averaged to that size, pixel for pixel (PNG is lossless).
  cv::Mat small;
  cv::resize(panorama, small, decoded.size(), 0, 0, cv::INTER_AREA);
  EXPECT_EQ(cv::norm(small, decoded, cv::NORM_INF), 0.0);
}

TEST(Thumbnail, AMissingOrBrokenThumbnailNamesThePlace) {
  for (const std::vector<std::uint8_t>& png :
       {std::vector<std::uint8_t>{}, std::vector<std::uint8_t>{1, 2, 3}}) {
    try {
      decode_thumbnail(png, "place 7");
      FAIL() << "no error";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("place 7"), std::string::npos) << error.what();
    }
  }
}

}  // namespace
}  // namespace omninav::memory
