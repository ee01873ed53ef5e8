// Circular column resampling (resample.hpp), for running the compass at another resolution.
#include "omninav/compass/resample.hpp"

#include <gtest/gtest.h>

#include "compass_test_support.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"

namespace omninav::compass {
namespace {

// Resampling keeps the azimuths: rolling by k columns at 360 and resampling to 1080 is the same
// as resampling and rolling by 3k (the filter is circular and the same for every column).
TEST(ResampleColumns, CommutesWithRollsAndKeepsTheFront) {
  const cv::Mat image = testing::random_image(360, 5, 3, 8);
  for (const int k : {1, 17, -90}) {
    EXPECT_EQ(cv::norm(resample_columns(roll_columns(image, k), 1080),
                       roll_columns(resample_columns(image, 1080), 3 * k), cv::NORM_INF),
              0.0)
        << k;
    EXPECT_EQ(cv::norm(resample_columns(roll_columns(resample_columns(image, 1080), 3 * k), 360),
                       roll_columns(resample_columns(resample_columns(image, 1080), 360), k),
                       cv::NORM_INF),
              0.0)
        << k;
  }
  // Enlarging by 3 keeps every original column at 3c (centres at integer positions).
  const cv::Mat large = resample_columns(image, 1080);
  for (int c = 0; c < 360; c += 7) {
    EXPECT_EQ(cv::norm(large.col(3 * c), image.col(c), cv::NORM_INF), 0.0) << c;
  }
  // A vertical stripe at the front stays at the front.
  cv::Mat stripe(4, 1080, CV_8UC1, cv::Scalar(0));
  stripe.colRange(267, 274).setTo(255);  // centred on column 270 = 0.25·1080
  const cv::Mat small = resample_columns(stripe, 360);
  cv::Point peak;
  cv::minMaxLoc(small.row(0), nullptr, nullptr, nullptr, &peak);
  EXPECT_EQ(peak.x, 90);
}

TEST(ResampleColumns, WrapsRoundAndKeepsUniformImagesUniform) {
  const cv::Mat uniform(3, 180, CV_8UC3, cv::Scalar(12, 200, 77));
  for (const int width : {90, 180, 360, 1080, 7}) {
    const cv::Mat resampled = resample_columns(uniform, width);
    EXPECT_EQ(resampled.cols, width);
    EXPECT_EQ(resampled.rows, 3);
    EXPECT_EQ(
        cv::norm(resampled, cv::Mat(3, width, CV_8UC3, cv::Scalar(12, 200, 77)), cv::NORM_INF),
        0.0);
  }
  EXPECT_THROW(resample_columns(cv::Mat(), 360), InputError);
  EXPECT_THROW(resample_columns(uniform, 0), UsageError);
}

}  // namespace
}  // namespace omninav::compass
