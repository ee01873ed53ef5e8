// Unwrapping against ground truth by construction: round trips through wrap_panorama, raw
// images rotated about the mirror centre, and bright spots placed at known raw directions.

#include "omninav/omni/unwrap.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <ostream>
#include <sstream>
#include <string>

#include "omni/synthetic_images.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/panorama.hpp"

namespace omninav::omni {
namespace {

using testing::bright_column;
using testing::bright_row;
using testing::column_difference;
using testing::mean_abs_error;
using testing::textured_panorama;

const cv::Size kRawSize(640, 640);

// A 640×640 raw image with an off-centre, non-integer centre, in pixels.
UnwrapParams synthetic_camera(int width_px, int height_px) {
  UnwrapParams params;
  params.units = LengthUnits::kPixels;
  params.centre_x = 317.25;
  params.centre_y = 322.5;
  params.inner_radius = 60.0;
  params.outer_radius = 300.0;
  params.width_px = width_px;
  params.height_px = height_px;
  return params;
}

struct RoundTripCase {
  Interpolation unwrap_interpolation;
  bool flip;
  double front_offset_deg;
  bool outer_radius_at_top;
  double tolerance;

  std::string name() const {
    std::ostringstream text;
    text << to_string(unwrap_interpolation) << (flip ? "_flip" : "_noflip") << "_front"
         << (front_offset_deg < 0 ? "minus" : "") << std::abs(front_offset_deg)
         << (outer_radius_at_top ? "_outertop" : "_innertop");
    return text.str();
  }
  friend std::ostream& operator<<(std::ostream& out, const RoundTripCase& test) {
    return out << test.name();
  }
};

class RoundTrip : public ::testing::TestWithParam<RoundTripCase> {};

// wrap_panorama then unwrap gives the panorama back. The raw image is made with bilinear
// sampling either way. Tolerances, mean absolute error in grey levels per pixel and channel:
//   bilinear 0.1: the raw annulus holds 1 (inner ring) to 5 (rim) pixels per panorama pixel, so
//     sampling it again at the panorama's pixel centres nearly restores them; measured 0.013.
//   nearest 0.4: reading the nearest raw pixel moves a sample by up to half a raw pixel, about
//     half a column at the inner ring, where the error is largest; measured 0.15.
// For scale, on this texture a panorama half a column off costs 1.2 and half a row off 0.97, so
// an off-by-half error in the column or row convention fails both.
TEST_P(RoundTrip, UnwrapInvertsWrap) {
  const RoundTripCase& test = GetParam();
  const cv::Mat panorama = textured_panorama(360, 45);
  UnwrapParams params = synthetic_camera(360, 45);
  params.flip = test.flip;
  params.front_offset_rad = deg_to_rad(test.front_offset_deg);
  params.outer_radius_at_top = test.outer_radius_at_top;
  params.interpolation = Interpolation::kBilinear;
  const cv::Mat raw = wrap_panorama(panorama, params, kRawSize);
  ASSERT_EQ(raw.size(), kRawSize);

  params.interpolation = test.unwrap_interpolation;
  const Unwrapper unwrapper(params, kRawSize);
  const cv::Mat unwrapped = unwrapper.unwrap(raw);
  ASSERT_EQ(unwrapped.size(), panorama.size());
  ASSERT_EQ(unwrapped.type(), panorama.type());
  EXPECT_LT(mean_abs_error(unwrapped, panorama), test.tolerance);
  // Not trivially small because of a bug that returns a constant: the texture is far from it.
  EXPECT_GT(
      mean_abs_error(unwrapped, cv::Mat(panorama.size(), panorama.type(), cv::mean(panorama))),
      20.0);
}

INSTANTIATE_TEST_SUITE_P(
    Omni, RoundTrip,
    ::testing::Values(RoundTripCase{Interpolation::kBilinear, false, 0.0, true, 0.1},
                      RoundTripCase{Interpolation::kBilinear, true, 0.0, true, 0.1},
                      RoundTripCase{Interpolation::kBilinear, false, 37.0, false, 0.1},
                      RoundTripCase{Interpolation::kBilinear, true, -120.0, true, 0.1},
                      RoundTripCase{Interpolation::kNearest, false, 0.0, true, 0.4},
                      RoundTripCase{Interpolation::kNearest, true, 90.0, false, 0.4}),
    [](const auto& info) { return info.param.name(); });

TEST(Wrap, OutsideTheAnnulusIsBlackAndInsideIsNot) {
  const UnwrapParams params = synthetic_camera(360, 45);
  const cv::Mat raw = wrap_panorama(textured_panorama(360, 45, 50.0, 235.0), params, kRawSize);
  // The centre (inside the inner circle), a corner and just outside the rim: black.
  EXPECT_EQ(raw.at<cv::Vec3b>(322, 317), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(raw.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(raw.at<cv::Vec3b>(322, 317 + 302), cv::Vec3b(0, 0, 0));
  // Mid-annulus: textured, never below the panorama's minimum.
  const cv::Vec3b inside = raw.at<cv::Vec3b>(322, 317 + 180);
  EXPECT_GE(inside[0], 50);
  EXPECT_GE(inside[1], 50);
  EXPECT_GE(inside[2], 50);
}

TEST(Wrap, GreyPanoramaGivesGreyRaw) {
  cv::Mat grey;
  cv::cvtColor(textured_panorama(360, 45), grey, cv::COLOR_BGR2GRAY);
  const UnwrapParams params = synthetic_camera(360, 45);
  const cv::Mat raw = wrap_panorama(grey, params, kRawSize);
  EXPECT_EQ(raw.type(), CV_8UC1);
  const cv::Mat unwrapped = Unwrapper(params, kRawSize).unwrap(raw);
  EXPECT_EQ(unwrapped.type(), CV_8UC1);
  EXPECT_LT(mean_abs_error(unwrapped, grey), 0.1);  // as RoundTrip, bilinear
}

// The best integer roll of `panorama` onto `reference` (least mean absolute error).
int best_roll(const cv::Mat& panorama, const cv::Mat& reference) {
  int best = 0;
  double best_error = 1e300;
  for (int shift = 0; shift < panorama.cols; ++shift) {
    const double error = mean_abs_error(roll_columns(reference, shift), panorama);
    if (error < best_error) {
      best_error = error;
      best = shift;
    }
  }
  return best;
}

struct RotationCase {
  int width_px;
  double raw_rotation_deg;  // counter-clockwise on screen
  bool flip;

  std::string name() const {
    std::ostringstream text;
    text << "W" << width_px << "_raw_ccw" << raw_rotation_deg << (flip ? "_flip" : "_noflip");
    return text.str();
  }
  friend std::ostream& operator<<(std::ostream& out, const RotationCase& test) {
    return out << test.name();
  }
};

class RawRotation : public ::testing::TestWithParam<RotationCase> {};

// Rotating the raw image about the mirror centre is a rotation of the robot on the spot.
// flip = false (raw image = view from above): the raw content turning counter-clockwise by k is
// the robot turning CLOCKWISE by k, so the panorama content moves by shift_px_of_rotation(−k)
// = −k·W/360 columns (docs/design.md: a counter-clockwise turn moves it to higher columns).
// flip = true (mirrored raw image): the same raw rotation is a counter-clockwise turn, +k·W/360.
// The roll must be the best of all W rolls, and match within interpolation error: 0.3 grey
// levels (measured up to 0.09: warpAffine interpolates the raw image once more); one column off
// costs 2.4 (W = 360) or 1.2 (W = 720) on this texture.
TEST_P(RawRotation, RollsThePanoramaByTheTurn) {
  const RotationCase& test = GetParam();
  UnwrapParams params = synthetic_camera(test.width_px, 45);
  params.flip = test.flip;
  const cv::Mat raw = wrap_panorama(textured_panorama(test.width_px, 45), params, kRawSize);
  const cv::Point2f centre(static_cast<float>(*params.centre_x),
                           static_cast<float>(*params.centre_y));
  // OpenCV: a positive angle rotates the content counter-clockwise on screen (y down).
  const cv::Mat rotation = cv::getRotationMatrix2D(centre, test.raw_rotation_deg, 1.0);
  cv::Mat rotated;
  cv::warpAffine(raw, rotated, rotation, raw.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);

  const Unwrapper unwrapper(params, kRawSize);
  const cv::Mat before = unwrapper.unwrap(raw);
  const cv::Mat after = unwrapper.unwrap(rotated);

  const double robot_turn_rad =
      deg_to_rad(test.flip ? test.raw_rotation_deg : -test.raw_rotation_deg);
  const double expected_shift = shift_px_of_rotation(robot_turn_rad, test.width_px);
  ASSERT_DOUBLE_EQ(expected_shift, std::round(expected_shift));  // whole columns in these cases
  const int expected = static_cast<int>(std::round(expected_shift));
  const int found = best_roll(after, before);
  EXPECT_EQ(found, ((expected % test.width_px) + test.width_px) % test.width_px)
      << "expected a roll of " << expected << " columns";
  EXPECT_LT(mean_abs_error(after, roll_columns(before, expected)), 0.3);
}

INSTANTIATE_TEST_SUITE_P(
    Omni, RawRotation,
    ::testing::Values(RotationCase{360, 10.0, false}, RotationCase{360, 45.0, false},
                      RotationCase{360, 90.0, false}, RotationCase{720, 10.0, false},
                      RotationCase{720, 45.0, false}, RotationCase{720, 90.0, false},
                      RotationCase{360, 10.0, true}, RotationCase{360, 45.0, true},
                      RotationCase{360, 90.0, true}, RotationCase{720, 10.0, true},
                      RotationCase{720, 45.0, true}, RotationCase{720, 90.0, true}),
    [](const auto& info) { return info.param.name(); });

// A spot in a black raw image, unwrapped: where does it land?
struct SpotLanding {
  double column;
  double row;
};

SpotLanding unwrap_spot(const UnwrapParams& params, cv::Point2d spot) {
  cv::Mat raw(kRawSize, CV_8UC1, cv::Scalar(0));
  testing::add_spot(raw, spot);
  const cv::Mat panorama = Unwrapper(params, kRawSize).unwrap(raw);
  return {bright_column(panorama), bright_row(panorama)};
}

// Raw positions written out by hand (not with the library's formula): centre (317.25, 322.5),
// mid-annulus radius 180 px. "Up" is −y in the image.
const double kCx = 317.25;
const double kCy = 322.5;
const double kRho = 180.0;
const cv::Point2d kUp(kCx, kCy - kRho);
const cv::Point2d kLeft(kCx - kRho, kCy);
const cv::Point2d kDown(kCx, kCy + kRho);
const cv::Point2d kRight(kCx + kRho, kCy);

// The spots are about 0.6 column wide (σ 2 px at 180 px radius is 0.64°) and bilinear sampling
// is symmetric, so their centroid lands on the spot's column: measured within 0.02 column.
// Tolerance 0.1 column: a half-column slip in the convention (pixel centres vs edges) fails.
constexpr double kColumnTolerance = 0.1;

TEST(ColumnConvention, FrontAtTheTopLandsAtAQuarterOfTheWidth) {
  for (const int width : {360, 720}) {
    const UnwrapParams params = synthetic_camera(width, 45);  // front_offset 0: front is up
    EXPECT_NEAR(column_difference(unwrap_spot(params, kUp).column, 0.25 * width, width), 0.0,
                kColumnTolerance)
        << "width " << width;
  }
}

TEST(ColumnConvention, LeftLandsAtColumnZeroAndRightAtThreeQuarters) {
  const int width = 360;
  const UnwrapParams params = synthetic_camera(width, 45);
  // flip = false, front up: the robot's left is on the raw image's left (view from above).
  EXPECT_NEAR(column_difference(unwrap_spot(params, kLeft).column, 0.0, width), 0.0,
              kColumnTolerance);
  EXPECT_NEAR(column_difference(unwrap_spot(params, kRight).column, 0.5 * width, width), 0.0,
              kColumnTolerance);  // the right: azimuth −90°, column 0.5·W
  EXPECT_NEAR(column_difference(unwrap_spot(params, kDown).column, 0.75 * width, width), 0.0,
              kColumnTolerance);  // the back
}

TEST(ColumnConvention, FlipSwapsLeftAndRight) {
  const int width = 360;
  UnwrapParams params = synthetic_camera(width, 45);
  params.flip = true;
  EXPECT_NEAR(column_difference(unwrap_spot(params, kUp).column, 0.25 * width, width), 0.0,
              kColumnTolerance);  // the front stays
  EXPECT_NEAR(column_difference(unwrap_spot(params, kRight).column, 0.0, width), 0.0,
              kColumnTolerance);  // mirrored: the robot's left is on the raw image's right
  EXPECT_NEAR(column_difference(unwrap_spot(params, kLeft).column, 0.5 * width, width), 0.0,
              kColumnTolerance);
}

TEST(ColumnConvention, FrontOffsetIsCounterClockwiseFromUp) {
  const int width = 360;
  UnwrapParams params = synthetic_camera(width, 45);
  params.front_offset_rad = deg_to_rad(90.0);  // front on the raw image's left
  EXPECT_NEAR(column_difference(unwrap_spot(params, kLeft).column, 0.25 * width, width), 0.0,
              kColumnTolerance);
  EXPECT_NEAR(column_difference(unwrap_spot(params, kDown).column, 0.0, width), 0.0,
              kColumnTolerance);  // 90° counter-clockwise of the front: the left (no flip)
  params.front_offset_rad = deg_to_rad(-90.0);  // front on the raw image's right
  EXPECT_NEAR(column_difference(unwrap_spot(params, kRight).column, 0.25 * width, width), 0.0,
              kColumnTolerance);
  params.front_offset_rad = deg_to_rad(30.0);  // up and to the left: φ = 30°
  const cv::Point2d front(kCx - kRho * std::sin(deg_to_rad(30.0)),
                          kCy - kRho * std::cos(deg_to_rad(30.0)));
  EXPECT_NEAR(column_difference(unwrap_spot(params, front).column, 0.25 * width, width), 0.0,
              kColumnTolerance);
}

TEST(RowConvention, OuterRadiusAtTopUnlessAskedOtherwise) {
  UnwrapParams params = synthetic_camera(360, 45);
  // Radius 290 px is 10 px inside the 300 px rim: (300 − 290)/(240/45) − 0.5 = 1.375 rows down.
  const cv::Point2d near_rim(kCx, kCy - 290.0);
  EXPECT_NEAR(unwrap_spot(params, near_rim).row, 1.375, 0.2);  // half a row off fails
  params.outer_radius_at_top = false;
  EXPECT_NEAR(unwrap_spot(params, near_rim).row, 45 - 1 - 1.375, 0.2);
}

TEST(Unwrapper, FractionsAreOfTheRawWidth) {
  // The same annulus given in fractions of the 640 px width and in pixels: identical output.
  UnwrapParams fractions;
  fractions.centre_x = 317.25 / 640.0;
  fractions.centre_y = 322.5 / 640.0;
  fractions.inner_radius = 60.0 / 640.0;
  fractions.outer_radius = 300.0 / 640.0;
  const cv::Mat raw =
      wrap_panorama(textured_panorama(360, 45), synthetic_camera(360, 45), kRawSize);
  const cv::Mat from_fractions = Unwrapper(fractions, kRawSize).unwrap(raw);
  const cv::Mat from_pixels = Unwrapper(synthetic_camera(360, 45), kRawSize).unwrap(raw);
  EXPECT_LT(mean_abs_error(from_fractions, from_pixels), 0.01);
}

TEST(Unwrapper, PixProPublishedFractionsResolveToWholePixelsOn1440) {
  // shared/data/README.md: centre (0.50694, 0.51042), radii 0.09375 and 0.49028 of the width;
  // on the camera's 1440×1440 images they are the whole pixels its unwrapper was given.
  UnwrapParams pixpro;
  pixpro.centre_x = 0.50694;
  pixpro.centre_y = 0.51042;
  pixpro.inner_radius = 0.09375;
  pixpro.outer_radius = 0.49028;
  const Annulus annulus = resolve_annulus(pixpro, cv::Size(1440, 1440));
  EXPECT_NEAR(annulus.centre_px.x, 730.0, 0.01);
  EXPECT_NEAR(annulus.centre_px.y, 735.0, 0.01);
  EXPECT_NEAR(annulus.inner_radius_px, 135.0, 0.01);
  EXPECT_NEAR(annulus.outer_radius_px, 706.0, 0.01);
}

TEST(Unwrapper, InnerRadiusDefaultsToAFractionOfTheOuter) {
  UnwrapParams params = synthetic_camera(360, 45);
  params.inner_radius.reset();
  params.inner_fraction_of_outer = 0.25;
  EXPECT_NEAR(resolve_annulus(params, kRawSize).inner_radius_px, 75.0, 1e-9);
}

}  // namespace
}  // namespace omninav::omni
