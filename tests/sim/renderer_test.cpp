#include "omninav/sim/renderer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "omninav/core/angles.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/sim/room.hpp"
#include "test_worlds.hpp"

namespace omninav::sim {
namespace {

RenderParams params_for(int width, int height, double elevation_min_deg, double elevation_max_deg) {
  RenderParams params;
  params.geometry.width_px = width;
  params.geometry.height_px = height;
  params.geometry.elevation_min_rad = deg_to_rad(elevation_min_deg);
  params.geometry.elevation_max_rad = deg_to_rad(elevation_max_deg);
  return params;
}

double mean_abs_difference(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat difference;
  cv::absdiff(a, b, difference);
  const cv::Scalar mean = cv::mean(difference);
  return (mean[0] + mean[1] + mean[2]) / 3.0;
}

class DefaultRoom : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { room_ = new World(make_room({})); }
  static void TearDownTestSuite() { delete room_; }
  static World* room_;
};
World* DefaultRoom::room_ = nullptr;

TEST_F(DefaultRoom, TurningByWholeColumnsRollsThePanoramaExactly) {
  for (int width : {360, 720}) {
    const Renderer renderer(*room_, params_for(width, 30, -30, 15));
    const CameraPose pose{2.2, 1.7, 1.0, deg_to_rad(33.3), 0.0, 0.0};
    const cv::Mat reference = renderer.render(pose);
    for (int columns : {1, 7, 90, -45, 359}) {
      CameraPose turned = pose;
      turned.heading_rad = pose.heading_rad + rotation_of_shift_px(columns, width);
      const cv::Mat rendered = renderer.render(turned);
      EXPECT_EQ(cv::norm(rendered, roll_columns(reference, columns), cv::NORM_INF), 0.0)
          << "width " << width << ", turn of " << columns << " columns";
    }
  }
}

TEST_F(DefaultRoom, SubColumnTurnsChangeTheImageAndMatchAFractionalRoll) {
  const int width = 360;
  const Renderer renderer(*room_, params_for(width, 45, -30, 15));
  const CameraPose pose{3.1, 2.4, 1.0, 0.4, 0.0, 0.0};
  const cv::Mat reference = renderer.render(pose);
  for (double fraction : {0.25, 0.5}) {
    CameraPose turned = pose;
    turned.heading_rad += rotation_of_shift_px(fraction, width);
    const cv::Mat rendered = renderer.render(turned);
    // Anti-aliasing makes a quarter-column turn visible...
    EXPECT_GT(mean_abs_difference(rendered, reference), 0.5) << fraction;
    // ...and the result is close to interpolating between whole-column rolls. Tolerance: linear
    // interpolation is not the renderer's box filter over sub-rays; measured about 1 grey level
    // on this room, 3 allows for other rooms while a wrong sign or size of shift gives > 5.
    EXPECT_LT(mean_abs_difference(rendered, roll_columns_fractional(reference, fraction)), 3.0)
        << fraction;
    EXPECT_GT(mean_abs_difference(rendered, roll_columns_fractional(reference, -fraction)),
              mean_abs_difference(rendered, roll_columns_fractional(reference, fraction)));
  }
}

TEST_F(DefaultRoom, PlacesThirtyCentimetresApartLookDifferent) {
  const Renderer renderer(*room_, params_for(360, 45, -30, 15));
  // Turning on the spot by one degree is the scale of change the compass must beat; a 30 cm
  // step must change the image clearly more than image noise (a few grey levels) would.
  for (double x : {1.5, 2.5, 3.5}) {
    const cv::Mat here = renderer.render({x, 2.0, 1.0, 0.0, 0.0, 0.0});
    const cv::Mat there = renderer.render({x + 0.3, 2.0, 1.0, 0.0, 0.0, 0.0});
    EXPECT_GT(mean_abs_difference(here, there), 8.0) << "at x = " << x;
  }
}

TEST_F(DefaultRoom, RenderingIsDeterministic) {
  const Renderer renderer(*room_, params_for(360, 45, -30, 15));
  const CameraPose pose{1.3, 1.1, 0.9, 1.0, 0.02, -0.03};
  EXPECT_EQ(cv::norm(renderer.render(pose), renderer.render(pose), cv::NORM_INF), 0.0);
  const World same_room = make_room({});
  const Renderer again(same_room, params_for(360, 45, -30, 15));
  EXPECT_EQ(cv::norm(renderer.render(pose), again.render(pose), cv::NORM_INF), 0.0);
  RoomParams other;
  other.seed = 2;
  const Renderer other_room(make_room(other), params_for(360, 45, -30, 15));
  EXPECT_GT(mean_abs_difference(renderer.render(pose), other_room.render(pose)), 10.0);
}

// The centroid of the clearly red pixels, as (column offset from `near_column` wrapped to
// ±W/2, row), so that an object straddling the panorama's seam is measured correctly.
cv::Point2d red_centroid_near(const cv::Mat& panorama, double near_column) {
  double sum_offset = 0.0, sum_row = 0.0;
  int count = 0;
  for (int row = 0; row < panorama.rows; ++row) {
    for (int column = 0; column < panorama.cols; ++column) {
      const cv::Vec3b pixel = panorama.at<cv::Vec3b>(row, column);
      if (pixel[2] > 100 && pixel[1] < 60 && pixel[0] < 60) {
        sum_offset += std::remainder(column - near_column, panorama.cols);
        sum_row += row;
        ++count;
      }
    }
  }
  if (count == 0) return {1e9, 1e9};
  return {sum_offset / count, sum_row / count};
}

TEST(Renderer, AnObjectAppearsAtItsPredictedBearingAndElevation) {
  const int width = 720, height = 180;
  const RenderParams params = params_for(width, height, -45, 45);
  // A small red cube 4 m away, seen from a camera at the origin with various headings.
  struct Case {
    double bearing_deg, elevation_deg, heading_deg;
  };
  for (const Case& c : {Case{0, 0, 0}, Case{30, 10, 0}, Case{-100, -10, 45}, Case{170, 25, -60},
                        Case{90, -5, 200}}) {
    World world = testing::horizon_hall(20.0, 1.0, 30.0);
    const double world_azimuth = deg_to_rad(c.bearing_deg + c.heading_deg);
    const double distance = 4.0, camera_z = 1.0;
    const cv::Vec3f centre(
        static_cast<float>(distance * std::cos(deg_to_rad(c.elevation_deg)) *
                           std::cos(world_azimuth)),
        static_cast<float>(distance * std::cos(deg_to_rad(c.elevation_deg)) *
                           std::sin(world_azimuth)),
        static_cast<float>(camera_z + distance * std::sin(deg_to_rad(c.elevation_deg))));
    testing::add_coloured_box(world, centre, 0.1f, {0.f, 0.f, 255.f});
    const Renderer renderer(world, params);
    const cv::Mat panorama =
        renderer.render({0.0, 0.0, camera_z, deg_to_rad(c.heading_deg), 0.0, 0.0});
    const double column = column_of_azimuth(deg_to_rad(c.bearing_deg), width);
    const double row = params.geometry.row_of_elevation(deg_to_rad(c.elevation_deg));
    const cv::Point2d found = red_centroid_near(panorama, column);
    // The cube spans about 1.4° (3 px); its centroid is within half a pixel of its centre.
    EXPECT_NEAR(found.x, 0.0, 0.5) << "bearing " << c.bearing_deg;
    EXPECT_NEAR(found.y, row, 0.5) << "elevation " << c.elevation_deg;
  }
}

// The sub-pixel row where a column goes from white (above) to black (below).
double horizon_row(const cv::Mat& panorama, int column) {
  cv::Mat grey;
  cv::cvtColor(panorama, grey, cv::COLOR_BGR2GRAY);
  // Threshold crossing at half the white level, interpolated between rows.
  const double white = grey.at<uchar>(0, column);
  for (int row = 1; row < grey.rows; ++row) {
    const double above = grey.at<uchar>(row - 1, column), below = grey.at<uchar>(row, column);
    if (above >= white / 2 && below < white / 2) {
      return row - 1 + (above - white / 2) / (above - below);
    }
  }
  return -1.0;
}

TEST(Renderer, PitchAndRollMoveTheHorizonAsPredicted) {
  const int width = 360, height = 120;
  const RenderParams params = params_for(width, height, -30, 30);
  // The walls' black/white edge is at the camera's height, 30 m away: the world horizon.
  const World world = testing::horizon_hall(30.0, 1.0, 60.0);
  const Renderer renderer(world, params);
  for (const auto& [pitch_deg, roll_deg] :
       {std::pair{0.0, 0.0}, std::pair{6.0, 0.0}, std::pair{0.0, 8.0}, std::pair{-4.0, 5.0}}) {
    const double pitch = deg_to_rad(pitch_deg), roll = deg_to_rad(roll_deg);
    const cv::Mat panorama = renderer.render({0.0, 0.0, 1.0, 0.7, pitch, roll});
    for (int column = 0; column < width; column += 15) {
      // A camera ray (azimuth a, elevation e) is level in the world when the third row of
      // Ry(pitch)·Rx(roll) is orthogonal to it:
      //   −sin p·cos e·cos a + cos p·sin r·cos e·sin a + cos p·cos r·sin e = 0.
      const double a = azimuth_of_column(column, width);
      const double elevation =
          std::atan2(std::sin(pitch) * std::cos(a) - std::cos(pitch) * std::sin(roll) * std::sin(a),
                     std::cos(pitch) * std::cos(roll));
      // Half a row: the edge is anti-aliased over one row and found by interpolation.
      EXPECT_NEAR(horizon_row(panorama, column), params.geometry.row_of_elevation(elevation), 0.5)
          << "pitch " << pitch_deg << "°, roll " << roll_deg << "°, column " << column;
    }
  }
}

TEST(Renderer, SensorEffects) {
  const World world = make_room({});
  RenderParams params = params_for(360, 45, -30, 15);
  const CameraPose pose{2.0, 2.0, 1.0, 0.0, 0.0, 0.0};
  const cv::Mat clean = Renderer(world, params).render(pose);

  params.effects.exposure_gain = 0.5;
  const cv::Mat dim = Renderer(world, params).render(pose);
  EXPECT_NEAR(cv::mean(dim)[1], cv::mean(clean)[1] * 0.5, 1.0);

  params.effects.exposure_gain = 1.0;
  params.effects.noise_stddev = 5.0;
  const Renderer noisy(world, params);
  const cv::Mat noisy_0 = noisy.render(pose, 0.0, 0);
  cv::Mat difference;
  cv::subtract(noisy_0, clean, difference, cv::noArray(), CV_32F);
  cv::Scalar mean, stddev;
  cv::meanStdDev(difference.reshape(1), mean, stddev);
  EXPECT_NEAR(stddev[0], 5.0, 0.5);  // clipping at 0 and 255 takes a little off
  EXPECT_EQ(cv::norm(noisy_0, noisy.render(pose, 0.0, 0), cv::NORM_INF), 0.0);  // seeded
  EXPECT_GT(cv::norm(noisy_0, noisy.render(pose, 0.0, 1), cv::NORM_INF), 0.0);  // per frame

  params.effects.noise_stddev = 0.0;
  params.effects.occluder.enabled = true;
  params.effects.occluder.from_x_m = 3.0;
  params.effects.occluder.from_y_m = 2.0;
  params.effects.occluder.to_x_m = 3.0;
  params.effects.occluder.to_y_m = 4.0;
  params.effects.occluder.speed_m_s = 1.0;
  const Renderer occluded(world, params);
  // At t = 0 the occluder stands 1 m ahead (+x, column 90); at t = 2 s it is 2 m to the left.
  const cv::Mat at_start = occluded.render(pose, 0.0);
  const cv::Mat later = occluded.render(pose, 2.0);
  // The column that changed most against the clean render.
  auto most_changed_column = [&](const cv::Mat& image) {
    cv::Mat difference_8u, grey, per_column;
    cv::absdiff(image, clean, difference_8u);
    cv::cvtColor(difference_8u, grey, cv::COLOR_BGR2GRAY);
    cv::reduce(grey, per_column, 0, cv::REDUCE_SUM, CV_64F);
    cv::Point peak;
    cv::minMaxLoc(per_column, nullptr, nullptr, nullptr, &peak);
    return peak.x;
  };
  // At t = 0 the occluder stands at (3, 2), 1 m straight ahead (column 90). At 1 m/s it is at
  // (3, 4) two seconds later, at azimuth atan2(2, 1) from the camera.
  EXPECT_NEAR(most_changed_column(occluded.render(pose, 0.0)), 90, 8);
  EXPECT_NEAR(most_changed_column(occluded.render(pose, 2.0)),
              column_of_azimuth(std::atan2(2.0, 1.0), 360), 8);
}

}  // namespace
}  // namespace omninav::sim
