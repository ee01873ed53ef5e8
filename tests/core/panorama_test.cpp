#include "omninav/core/panorama.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav {
namespace {

TEST(ColumnConvention, FrontLeftBackRight) {
  // docs/design.md: front at 0.25·W, back at 0.75·W, column 0 is the robot's left.
  const int width = 360;
  EXPECT_NEAR(azimuth_of_column(90, width), 0.0, 1e-12);
  EXPECT_NEAR(azimuth_of_column(0, width), kPi / 2, 1e-12);
  EXPECT_NEAR(azimuth_of_column(180, width), -kPi / 2, 1e-12);
  EXPECT_NEAR(std::abs(azimuth_of_column(270, width)), kPi, 1e-12);
  EXPECT_NEAR(column_of_azimuth(0.0, width), 90.0, 1e-9);
  EXPECT_NEAR(column_of_azimuth(kPi / 2, width), 0.0, 1e-9);
  EXPECT_NEAR(column_of_azimuth(-kPi / 2, width), 180.0, 1e-9);
}

TEST(ColumnConvention, ColumnAndAzimuthInvert) {
  for (int width : {360, 1080, 180}) {
    for (double column = 0.0; column < width; column += 0.7) {
      EXPECT_NEAR(column_of_azimuth(azimuth_of_column(column, width), width), column, 1e-9);
    }
  }
}

TEST(ColumnConvention, CounterClockwiseTurnShiftsContentToHigherColumns) {
  // An object at fixed world azimuth ψ sits at relative azimuth ψ − θ; turning by +δ lowers it.
  const int width = 360;
  const double object_world = deg_to_rad(30.0);
  const double heading = deg_to_rad(-10.0);
  const double turn = deg_to_rad(12.0);
  const double before = column_of_azimuth(object_world - heading, width);
  const double after = column_of_azimuth(object_world - heading - turn, width);
  EXPECT_NEAR(after - before, shift_px_of_rotation(turn, width), 1e-9);
  EXPECT_NEAR(after - before, 12.0, 1e-9);
  EXPECT_NEAR(rotation_of_shift_px(12.0, width), turn, 1e-12);
}

cv::Mat column_index_image(int width, int height) {
  cv::Mat image(height, width, CV_8UC3);
  for (int row = 0; row < height; ++row) {
    for (int column = 0; column < width; ++column) {
      image.at<cv::Vec3b>(row, column) = cv::Vec3b(column % 256, row, 7);
    }
  }
  return image;
}

TEST(RollColumns, MovesContentToHigherColumnsAndWraps) {
  const cv::Mat image = column_index_image(200, 4);
  for (int shift : {0, 1, 57, 199, 200, 201, -3, -450}) {
    const cv::Mat rolled = roll_columns(image, shift);
    for (int column = 0; column < 200; ++column) {
      const int target = ((column + shift) % 200 + 200) % 200;
      ASSERT_EQ(rolled.at<cv::Vec3b>(2, target), image.at<cv::Vec3b>(2, column)) << shift;
    }
  }
}

TEST(RollColumns, FractionalIsExactForWholeShiftsAndBlendsBetween) {
  const cv::Mat image = column_index_image(100, 2);
  EXPECT_EQ(cv::norm(roll_columns_fractional(image, 5.0), roll_columns(image, 5), cv::NORM_INF), 0);
  const cv::Mat half = roll_columns_fractional(image, 5.5);
  // Column 20 of the half-shifted image mixes old columns 15 and 14 equally.
  EXPECT_NEAR(half.at<cv::Vec3b>(0, 20)[0], 14.5, 0.51);
}

TEST(RequirePanorama, RejectsEmptyAndWrongTypes) {
  EXPECT_THROW(require_panorama(cv::Mat(), "x.png"), InputError);
  EXPECT_THROW(require_panorama(cv::Mat(4, 4, CV_32FC3), "x.png"), InputError);
  EXPECT_THROW(require_panorama(cv::Mat(4, 4, CV_8UC2), "x.png"), InputError);
  EXPECT_NO_THROW(require_panorama(cv::Mat(4, 4, CV_8UC3), "x.png"));
  EXPECT_NO_THROW(require_panorama(cv::Mat(4, 4, CV_8UC1), "x.png"));
  try {
    require_panorama(cv::Mat(), "frames/0003.png");
    FAIL();
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("frames/0003.png"), std::string::npos);
  }
}

TEST(PanoramaGeometry, RowsSpanTheElevationRange) {
  PanoramaGeometry geometry;
  geometry.height_px = 60;
  geometry.elevation_min_rad = deg_to_rad(-40.0);
  geometry.elevation_max_rad = deg_to_rad(20.0);
  EXPECT_NEAR(geometry.elevation_of_row(-0.5), deg_to_rad(20.0), 1e-12);   // top edge
  EXPECT_NEAR(geometry.elevation_of_row(59.5), deg_to_rad(-40.0), 1e-12);  // bottom edge
  EXPECT_NEAR(geometry.elevation_of_row(0), deg_to_rad(19.5), 1e-12);
  EXPECT_NEAR(geometry.row_of_elevation(0.0), 19.5, 1e-9);
}

}  // namespace
}  // namespace omninav

namespace omninav {
namespace {

// An RGB image said to be RGB becomes the BGR image it was made from, pixel for pixel; a BGR
// or grey image is left as it is; an unknown order is a usage error.
TEST(ChannelOrder, AnRgbImageBecomesTheBgrImageItWasMadeFrom) {
  cv::Mat bgr(4, 6, CV_8UC3);
  cv::randu(bgr, 0, 256);
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  ASSERT_NE(cv::norm(rgb, bgr, cv::NORM_INF), 0.0) << "the test image has no colour";
  EXPECT_EQ(cv::norm(to_bgr(rgb, ChannelOrder::kRgb), bgr, cv::NORM_INF), 0.0);
  EXPECT_EQ(to_bgr(bgr, ChannelOrder::kBgr).data, bgr.data) << "no copy when already BGR";
  const cv::Mat grey(4, 6, CV_8UC1, cv::Scalar(7));
  EXPECT_EQ(to_bgr(grey, ChannelOrder::kRgb).data, grey.data);
  EXPECT_EQ(channel_order_of("rgb"), ChannelOrder::kRgb);
  EXPECT_EQ(channel_order_of("bgr"), ChannelOrder::kBgr);
  EXPECT_THROW(channel_order_of("RGBA", "--channels"), UsageError);
}

}  // namespace
}  // namespace omninav
