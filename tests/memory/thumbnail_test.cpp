// A place's thumbnail (thumbnail.hpp): stored small, decoded again, and views brought to its size.
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
  // A panorama brought to the thumbnail's size is the thumbnail, pixel for pixel (PNG is
  // lossless): views and places are compared at one size.
  const cv::Mat view = as_thumbnail(panorama, decoded.size(), "view");
  EXPECT_EQ(cv::norm(view, decoded, cv::NORM_INF), 0.0);
}

TEST(Thumbnail, GreyViewsBecomeThreeChannels) {
  cv::Mat grey;
  cv::cvtColor(rendered_panorama(), grey, cv::COLOR_BGR2GRAY);
  const cv::Mat view = as_thumbnail(grey, cv::Size(90, 12), "view");
  EXPECT_EQ(view.size(), cv::Size(90, 12));
  EXPECT_EQ(view.channels(), 3);
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
  EXPECT_THROW(as_thumbnail(cv::Mat(), cv::Size(90, 12), "view"), InputError);
}

}  // namespace
}  // namespace omninav::memory
