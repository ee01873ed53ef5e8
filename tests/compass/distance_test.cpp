// The distance function (Eqs. 1-2 of Labrosse 2006) and its field of view (§3.4.3).
#include "omninav/compass/distance.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "compass_test_support.hpp"
#include "omninav/compass/field_of_view.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"

namespace omninav::compass {
namespace {

using testing::random_image;

TEST(ColumnMask, FrontAndBackBandsOfSixtyDegreesAt360Columns) {
  const ColumnMask mask = ColumnMask::front_back(360, deg_to_rad(60.0));
  // Column centres within ±30° of the front (column 90) and the back (column 270), inclusive.
  ASSERT_EQ(mask.runs().size(), 2u);
  EXPECT_EQ(mask.runs()[0], std::make_pair(60, 121));
  EXPECT_EQ(mask.runs()[1], std::make_pair(240, 301));
  EXPECT_EQ(mask.selected_count(), 122);
  // The front column looks straight ahead, the band edges 30° either side.
  EXPECT_NEAR(rad_to_deg(azimuth_of_column(90, 360)), 0.0, 1e-12);
  EXPECT_NEAR(rad_to_deg(azimuth_of_column(60, 360)), 30.0, 1e-12);
  EXPECT_NEAR(rad_to_deg(azimuth_of_column(120, 360)), -30.0, 1e-12);
}

TEST(ColumnMask, BandsScaleWithTheWidthAndMapOntoThemselvesUnderAHalfTurn) {
  for (const int width : {180, 360, 1080}) {
    const ColumnMask mask = ColumnMask::front_back(width, deg_to_rad(60.0));
    EXPECT_EQ(mask.selected_count(), 2 * (width / 6 + 1)) << width;
    for (int c = 0; c < width; ++c) {
      EXPECT_EQ(mask.selected(c), mask.selected((c + width / 2) % width)) << width << " " << c;
    }
  }
  EXPECT_TRUE(ColumnMask::front_back(360, deg_to_rad(180.0)).is_whole());
  EXPECT_TRUE(ColumnMask::whole(360).is_whole());
  EXPECT_NE(ColumnMask::whole(360).key(), ColumnMask::front_back(360, deg_to_rad(60.0)).key());
  EXPECT_EQ(ColumnMask::front_back(360, deg_to_rad(60.0)).key(),
            ColumnMask::front_back(360, deg_to_rad(60.0)).key());
}

// The fast kernel (on column-major copies and on rows) and the plain transcription of Eq. 2 are
// written independently; they must agree exactly, for every metric, mask, channel count and
// shift (including wrap-round).
TEST(DistanceFunction, FastKernelEqualsThePlainTranscriptionOfEquation2) {
  for (const int channels : {1, 3}) {
    for (const int width : {45, 180, 360}) {
      const CompassFrame first(random_image(width, 7, channels, 11 + width));
      const CompassFrame second(random_image(width, 7, channels, 23 + width));
      for (const Metric metric : {Metric::kL2, Metric::kL1}) {
        for (const bool front_back : {false, true}) {
          const DistanceFunction distance(
              metric, front_back ? ColumnMask::front_back(width, deg_to_rad(60.0))
                                 : ColumnMask::whole(width));
          for (int shift = -width; shift <= 2 * width; shift += 7) {
            const Cost reference = distance.reference_cost(first, second, shift);
            ASSERT_EQ(distance.cost(first, second, shift), reference)
                << "channels " << channels << " width " << width << " metric " << to_string(metric)
                << " mask " << front_back << " shift " << shift;
            ASSERT_EQ(distance.cost_on_rows(first, second, shift), reference)
                << "rows: channels " << channels << " width " << width << " metric "
                << to_string(metric) << " mask " << front_back << " shift " << shift;
          }
        }
      }
    }
  }
}

TEST(DistanceFunction, IsEquationOneAtShiftZeroAndTakesTheRoot) {
  cv::Mat a(2, 8, CV_8UC3, cv::Scalar(10, 20, 30));
  cv::Mat b(2, 8, CV_8UC3, cv::Scalar(13, 24, 30));
  const CompassFrame first(a), second(b);
  const DistanceFunction l2(Metric::kL2, ColumnMask::whole(8));
  const DistanceFunction l1(Metric::kL1, ColumnMask::whole(8));
  // 16 pixels, each (3² + 4² + 0²) = 25 → cost 400, distance 20.
  EXPECT_EQ(l2.cost(first, second, 0), 400);
  EXPECT_DOUBLE_EQ(l2.distance(400), 20.0);
  EXPECT_EQ(l1.cost(first, second, 0), 16 * 7);
  EXPECT_DOUBLE_EQ(l1.distance(112), 112.0);
  EXPECT_EQ(l2.compared_components(first), 2 * 3 * 8);
}

// Shifting the second image by α is roll_columns(second, α): a panorama rolled by s columns
// (what a counter-clockwise turn of s·360/W degrees does) matches its original at α = −s.
TEST(DistanceFunction, ARollBySColumnsIsUndoneByTheShiftMinusS) {
  const CompassFrame first(random_image(360, 9, 3, 5));
  for (const bool front_back : {false, true}) {
    const DistanceFunction distance(Metric::kL2, front_back
                                                     ? ColumnMask::front_back(360, deg_to_rad(60.0))
                                                     : ColumnMask::whole(360));
    for (const int s : {0, 1, 17, -40, 180, 359}) {
      const CompassFrame second(roll_columns(first.image(), s));
      EXPECT_EQ(distance.cost(first, second, -s), 0) << s;
      EXPECT_GT(distance.cost(first, second, -s + 1), 0) << s;
      // Shifting the second image by α really is rolling it: the cost equals the shift-0 cost
      // of the rolled image.
      const CompassFrame rolled(roll_columns(second.image(), 23));
      const DistanceFunction whole(Metric::kL2, ColumnMask::whole(360));
      EXPECT_EQ(whole.cost(first, second, 23), whole.cost(first, rolled, 0)) << s;
    }
  }
}

// The mask belongs to the second image and moves with it: pixels of the second image outside
// its front and back bands never count, at any shift.
TEST(DistanceFunction, PixelsOfTheSecondImageOutsideItsBandsNeverCount) {
  const CompassFrame first(random_image(360, 9, 3, 1));
  cv::Mat second_image = random_image(360, 9, 3, 2);
  const DistanceFunction distance(Metric::kL2, ColumnMask::front_back(360, deg_to_rad(60.0)));
  const CompassFrame second(second_image);
  cv::Mat changed = second_image.clone();
  changed.colRange(0, 60).setTo(cv::Scalar(255, 0, 255));   // the left side
  changed.colRange(121, 240).setTo(cv::Scalar(0, 255, 0));  // the right side
  changed.colRange(301, 360).setTo(cv::Scalar(0, 0, 0));    // the left side again
  const CompassFrame second_changed(changed);
  for (int shift = 0; shift < 360; ++shift) {
    ASSERT_EQ(distance.cost(first, second, shift), distance.cost(first, second_changed, shift))
        << shift;
  }
}

TEST(DistanceFunction, RefusesFramesOfDifferentShapes) {
  const DistanceFunction distance(Metric::kL2, ColumnMask::whole(360));
  const CompassFrame a(random_image(360, 9, 3, 1), 0, "a.png");
  const CompassFrame b(random_image(360, 10, 3, 1), 1, "b.png");
  const CompassFrame grey(random_image(360, 9, 1, 1), 2, "grey.png");
  const CompassFrame narrow(random_image(180, 9, 3, 1), 3, "narrow.png");
  EXPECT_THROW(distance.cost(a, b, 0), InputError);
  EXPECT_THROW(distance.cost(a, grey, 0), InputError);
  EXPECT_THROW(distance.cost(narrow, narrow, 0), InputError);  // not this function's width
  try {
    distance.cost(a, b, 0);
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("b.png"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("a.png"), std::string::npos) << error.what();
  }
}

TEST(CompassFrame, RefusesEmptyAndNon8BitImages) {
  EXPECT_THROW(CompassFrame(cv::Mat()), InputError);
  EXPECT_THROW(CompassFrame(cv::Mat(10, 10, CV_32FC3, cv::Scalar(0))), InputError);
  EXPECT_THROW(CompassFrame(cv::Mat(10, 10, CV_8UC4, cv::Scalar(0))), InputError);
  // A view into a bigger image is copied into one continuous block.
  const cv::Mat big = random_image(400, 20, 3, 3);
  const CompassFrame view(big(cv::Rect(10, 5, 360, 9)));
  EXPECT_TRUE(view.image().isContinuous());
  EXPECT_EQ(cv::norm(view.image(), big(cv::Rect(10, 5, 360, 9)), cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace omninav::compass
