// The `unwrap:` section of camera.yaml and the checks on bad parameters and bad input.

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/omni/unwrap.hpp"
#include "support/shared_data.hpp"

namespace omninav::omni {
namespace {

template <typename ErrorType>
std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const ErrorType& error) {
    return error.what();
  }
  return "(no error of the expected type)";
}

UnwrapParams valid_pixels() {
  UnwrapParams params;
  params.units = LengthUnits::kPixels;
  params.centre_x = 320.0;
  params.centre_y = 320.0;
  params.inner_radius = 60.0;
  params.outer_radius = 300.0;
  return params;
}

// The shipped config/camera.yaml documents the defaults: it must hold exactly the struct's
// defaults (so the file and the code cannot drift apart), and every key in it must be known.
TEST(CameraYaml, ShippedFileEqualsTheDefaultsAndHasNoUnknownKeys) {
  const ConfigReader camera =
      ConfigReader::from_file(omninav::testing::config_dir() / "camera.yaml");
  PanoramaGeometry geometry;
  load_panorama_geometry(camera.section("panorama"), geometry);
  UnwrapParams loaded = unwrap_params_for(geometry);
  load_unwrap_params(camera.section("unwrap"), loaded);
  EXPECT_NO_THROW(camera.require_all_known());

  const UnwrapParams defaults = unwrap_params_for(PanoramaGeometry{});
  EXPECT_EQ(loaded.units, defaults.units);
  EXPECT_EQ(loaded.centre_x, defaults.centre_x);
  EXPECT_EQ(loaded.centre_y, defaults.centre_y);
  EXPECT_EQ(loaded.inner_radius, defaults.inner_radius);
  EXPECT_EQ(loaded.outer_radius, defaults.outer_radius);
  EXPECT_DOUBLE_EQ(loaded.inner_fraction_of_outer, defaults.inner_fraction_of_outer);
  EXPECT_EQ(loaded.width_px, defaults.width_px);
  EXPECT_EQ(loaded.height_px, defaults.height_px);
  EXPECT_EQ(loaded.interpolation, defaults.interpolation);
  EXPECT_EQ(loaded.flip, defaults.flip);
  EXPECT_NEAR(loaded.front_offset_rad, defaults.front_offset_rad, 1e-12);
  EXPECT_EQ(loaded.outer_radius_at_top, defaults.outer_radius_at_top);
  // The struct's output size is the panorama section's default.
  EXPECT_EQ(UnwrapParams{}.width_px, PanoramaGeometry{}.width_px);
  EXPECT_EQ(UnwrapParams{}.height_px, PanoramaGeometry{}.height_px);
}

TEST(LoadUnwrapParams, ReadsEveryKey) {
  const ConfigReader camera = ConfigReader::from_string(
      "unwrap:\n"
      "  units: pixels\n"
      "  centre_x: 730\n"
      "  centre_y: 735\n"
      "  inner_radius: 135\n"
      "  outer_radius: 706\n"
      "  inner_fraction_of_outer: 0.3\n"
      "  interpolation: nearest\n"
      "  flip: true\n"
      "  front_offset_deg: -90\n"
      "  outer_radius_at_top: false\n",
      "camera.yaml");
  UnwrapParams params;
  load_unwrap_params(camera.section("unwrap"), params);
  EXPECT_NO_THROW(camera.require_all_known());
  EXPECT_EQ(params.units, LengthUnits::kPixels);
  EXPECT_EQ(params.centre_x, 730.0);
  EXPECT_EQ(params.centre_y, 735.0);
  EXPECT_EQ(params.inner_radius, 135.0);
  EXPECT_EQ(params.outer_radius, 706.0);
  EXPECT_DOUBLE_EQ(params.inner_fraction_of_outer, 0.3);
  EXPECT_EQ(params.interpolation, Interpolation::kNearest);
  EXPECT_TRUE(params.flip);
  EXPECT_NEAR(params.front_offset_rad, deg_to_rad(-90.0), 1e-12);
  EXPECT_FALSE(params.outer_radius_at_top);
}

TEST(LoadUnwrapParams, NullCentreMeansDetect) {
  const ConfigReader camera =
      ConfigReader::from_string("unwrap:\n  centre_x: ~\n  centre_y: ~\n", "camera.yaml");
  UnwrapParams params = valid_pixels();
  load_unwrap_params(camera.section("unwrap"), params);
  EXPECT_FALSE(params.centre_x.has_value());
  EXPECT_FALSE(params.centre_y.has_value());
}

TEST(LoadUnwrapParams, UnknownKeyIsAConfigErrorNamingIt) {
  const ConfigReader camera = ConfigReader::from_string(
      "unwrap:\n  centre_x: 0.5\n  centre_y: 0.5\n  radius_outer: 0.45\n", "config/camera.yaml");
  UnwrapParams params;
  load_unwrap_params(camera.section("unwrap"), params);
  const std::string message = message_of<ConfigError>([&] { camera.require_all_known(); });
  EXPECT_NE(message.find("unwrap.radius_outer"), std::string::npos) << message;
  EXPECT_NE(message.find("config/camera.yaml"), std::string::npos) << message;
  EXPECT_NE(message.find("outer_radius"), std::string::npos) << message;  // the known keys
}

TEST(LoadUnwrapParams, FractionOutOfRangeNamesTheKeyAndRange) {
  const ConfigReader camera = ConfigReader::from_string(
      "unwrap:\n  outer_radius: 706\n", "camera.yaml");  // pixels, but units say fraction
  UnwrapParams params;
  const std::string message =
      message_of<ConfigError>([&] { load_unwrap_params(camera.section("unwrap"), params); });
  EXPECT_NE(message.find("unwrap.outer_radius"), std::string::npos) << message;
  EXPECT_NE(message.find("out of range"), std::string::npos) << message;
}

TEST(LoadUnwrapParams, BadChoicesAreConfigErrors) {
  UnwrapParams params;
  const ConfigReader units = ConfigReader::from_string("unwrap:\n  units: mm\n", "camera.yaml");
  EXPECT_THROW(load_unwrap_params(units.section("unwrap"), params), ConfigError);
  const ConfigReader interpolation =
      ConfigReader::from_string("unwrap:\n  interpolation: cubic\n", "camera.yaml");
  EXPECT_THROW(load_unwrap_params(interpolation.section("unwrap"), params), ConfigError);
  const ConfigReader offset =
      ConfigReader::from_string("unwrap:\n  front_offset_deg: 400\n", "camera.yaml");
  EXPECT_THROW(load_unwrap_params(offset.section("unwrap"), params), ConfigError);
}

TEST(LoadUnwrapParams, InnerNotBelowOuterIsAConfigError) {
  const ConfigReader camera = ConfigReader::from_string(
      "unwrap:\n  inner_radius: 0.4\n  outer_radius: 0.3\n", "camera.yaml");
  UnwrapParams params;
  const std::string message =
      message_of<ConfigError>([&] { load_unwrap_params(camera.section("unwrap"), params); });
  EXPECT_NE(message.find("inner_radius"), std::string::npos) << message;
  EXPECT_NE(message.find("smaller"), std::string::npos) << message;
}

TEST(LoadUnwrapParams, CentreXWithoutCentreYIsAConfigError) {
  const ConfigReader camera =
      ConfigReader::from_string("unwrap:\n  centre_x: 0.5\n", "camera.yaml");
  UnwrapParams params;
  const std::string message =
      message_of<ConfigError>([&] { load_unwrap_params(camera.section("unwrap"), params); });
  EXPECT_NE(message.find("centre_y"), std::string::npos) << message;
}

TEST(Unwrapper, InnerNotBelowOuterIsAConfigError) {
  UnwrapParams params = valid_pixels();
  params.inner_radius = 300.0;
  EXPECT_THROW(Unwrapper(params, cv::Size(640, 640)), ConfigError);
  params.inner_radius = 350.0;
  const std::string message =
      message_of<ConfigError>([&] { Unwrapper(params, cv::Size(640, 640)); });
  EXPECT_NE(message.find("inner radius"), std::string::npos) << message;
  EXPECT_THROW(wrap_panorama(cv::Mat(45, 360, CV_8UC1, cv::Scalar(1)), params, {640, 640}),
               ConfigError);
}

TEST(Unwrapper, RawOfAnotherSizeIsAnInputError) {
  const Unwrapper unwrapper(valid_pixels(), cv::Size(640, 640));
  const std::string message = message_of<InputError>(
      [&] { unwrapper.unwrap(cv::Mat(480, 640, CV_8UC3, cv::Scalar::all(0))); });
  EXPECT_NE(message.find("640×480"), std::string::npos) << message;
  EXPECT_NE(message.find("640×640"), std::string::npos) << message;
  EXPECT_THROW(unwrapper.unwrap(cv::Mat()), InputError);
}

TEST(Unwrapper, ZeroSizesAreErrors) {
  UnwrapParams params = valid_pixels();
  EXPECT_THROW(Unwrapper(params, cv::Size(0, 0)), InputError);
  params.width_px = 0;
  EXPECT_THROW(Unwrapper(params, cv::Size(640, 640)), ConfigError);
  params = valid_pixels();
  params.height_px = -3;
  EXPECT_THROW(Unwrapper(params, cv::Size(640, 640)), ConfigError);
  params = valid_pixels();
  params.outer_radius = 0.0;
  params.inner_radius = 0.0;
  EXPECT_THROW(Unwrapper(params, cv::Size(640, 640)), ConfigError);
  EXPECT_THROW(wrap_panorama(cv::Mat(), valid_pixels(), {640, 640}), InputError);
}

TEST(Unwrapper, CentreOutsideTheImageIsAConfigError) {
  UnwrapParams params = valid_pixels();
  params.centre_x = 700.0;
  const std::string message =
      message_of<ConfigError>([&] { Unwrapper(params, cv::Size(640, 640)); });
  EXPECT_NE(message.find("outside"), std::string::npos) << message;
}

TEST(Unwrapper, MissingCentreWithoutDetectionIsAConfigError) {
  UnwrapParams params = valid_pixels();
  params.centre_x.reset();
  params.centre_y.reset();
  const std::string message =
      message_of<ConfigError>([&] { Unwrapper(params, cv::Size(640, 640)); });
  EXPECT_NE(message.find("centre_x"), std::string::npos) << message;
}

TEST(Unwrapper, AnnulusBeyondTheImageStillUnwrapsWithBlackThere) {
  // Documented choice: a warning, not an error (published parameters of real cameras overshoot).
  UnwrapParams params = valid_pixels();
  params.outer_radius = 400.0;  // 80 px beyond every edge
  const Unwrapper unwrapper(params, cv::Size(640, 640));
  const cv::Mat white(640, 640, CV_8UC1, cv::Scalar(255));
  const cv::Mat panorama = unwrapper.unwrap(white);
  // Row 0 samples radius ~397 px: outside the image in every direction but the diagonals.
  EXPECT_EQ(panorama.at<uchar>(0, 0), 0);     // to the left, 77 px past the edge
  EXPECT_EQ(panorama.at<uchar>(44, 0), 255);  // the inner ring is inside
}

// A value set in code is refused by make_unwrapper as the YAML loader refuses it in camera.yaml,
// naming the key (UnwrapParams::check).
TEST(Unwrapper, ParamsOutOfRangeAreRefusedNamingTheKey) {
  UnwrapParams params;  // fractions of the raw width
  params.centre_x = 0.5;
  params.centre_y = 0.5;
  params.outer_radius = 1.5;
  const std::string message = message_of<ConfigError>(
      [&] { make_unwrapper(params, cv::Mat(cv::Size(64, 64), CV_8UC3, cv::Scalar::all(0))); });
  EXPECT_NE(message.find("unwrap.outer_radius"), std::string::npos) << message;
}

}  // namespace
}  // namespace omninav::omni
