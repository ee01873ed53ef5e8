#include "omninav/core/config.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav {
namespace {

std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "(no ConfigError)";
}

TEST(ConfigReader, ReadsTypedValuesAndKeepsDefaultsForAbsentKeys) {
  const ConfigReader config = ConfigReader::from_string(
      "panorama:\n  width_px: 720\n  fov_deg: 60\nflip: true\nmode: bilinear\n", "camera.yaml");
  int width = 360;
  int height = 45;
  double fov_rad = 0.0;
  bool flip = false;
  std::string mode = "nearest";
  const ConfigReader panorama = config.section("panorama");
  panorama.read("width_px", width, 8, 10000);
  panorama.read("height_px", height, 1, 1000);
  panorama.read_deg("fov_deg", fov_rad, 1.0, 180.0);
  config.read("flip", flip);
  config.read("mode", mode, {"nearest", "bilinear"});
  EXPECT_NO_THROW(config.require_all_known());
  EXPECT_EQ(width, 720);
  EXPECT_EQ(height, 45);
  EXPECT_NEAR(fov_rad, deg_to_rad(60.0), 1e-12);
  EXPECT_TRUE(flip);
  EXPECT_EQ(mode, "bilinear");
}

TEST(ConfigReader, UnknownKeyNamesTheKeyTheFileAndTheKnownOnes) {
  const ConfigReader config =
      ConfigReader::from_string("panorama:\n  widht_px: 720\n", "config/camera.yaml");
  int width = 360;
  config.section("panorama").read("width_px", width, 8, 10000);
  const std::string message = message_of([&] { config.require_all_known(); });
  EXPECT_NE(message.find("config/camera.yaml"), std::string::npos) << message;
  EXPECT_NE(message.find("panorama.widht_px"), std::string::npos) << message;
  EXPECT_NE(message.find("width_px"), std::string::npos) << message;
}

TEST(ConfigReader, OutOfRangeNamesTheKeyAndTheRange) {
  const ConfigReader config = ConfigReader::from_string("threshold: 1.5\n", "compass.yaml");
  double threshold = 0.6;
  const std::string message = message_of([&] { config.read("threshold", threshold, 0.0, 1.0); });
  EXPECT_NE(message.find("compass.yaml"), std::string::npos) << message;
  EXPECT_NE(message.find("'threshold'"), std::string::npos) << message;
  EXPECT_NE(message.find("[0, 1]"), std::string::npos) << message;
  EXPECT_DOUBLE_EQ(threshold, 0.6);  // untouched on error
}

TEST(ConfigReader, WrongTypesAreErrors) {
  const ConfigReader config = ConfigReader::from_string(
      "count: 2.5\nratio: abc\nflag: maybe\nmode: cubic\nsection: 3\n", "x.yaml");
  int count = 0;
  double ratio = 0;
  bool flag = false;
  std::string mode;
  EXPECT_THROW(config.read("count", count, 0, 10), ConfigError);
  EXPECT_THROW(config.read("ratio", ratio, 0, 10), ConfigError);
  EXPECT_THROW(config.read("flag", flag), ConfigError);
  EXPECT_THROW(config.read("mode", mode, {"nearest", "bilinear"}), ConfigError);
  EXPECT_THROW(config.section("section"), ConfigError);
}

TEST(ConfigReader, OptionalNumbersMayBeNull) {
  const ConfigReader config = ConfigReader::from_string("centre_x: ~\ncentre_y: 0.5\n", "c.yaml");
  std::optional<double> x = 3.0;
  std::optional<double> y;
  std::optional<double> z;
  config.read("centre_x", x, 0.0, 1.0);
  config.read("centre_y", y, 0.0, 1.0);
  config.read("centre_z", z, 0.0, 1.0);
  EXPECT_FALSE(x.has_value());
  ASSERT_TRUE(y.has_value());
  EXPECT_DOUBLE_EQ(*y, 0.5);
  EXPECT_FALSE(z.has_value());
}

TEST(ConfigReader, BadYamlAndMissingFilesAreErrorsNamingTheFile) {
  EXPECT_NE(message_of([] {
              ConfigReader::from_string("a: [1, 2\n", "broken.yaml");
            }).find("broken.yaml"),
            std::string::npos);
  EXPECT_NE(message_of([] {
              ConfigReader::from_file("/nonexistent/camera.yaml");
            }).find("/nonexistent/camera.yaml"),
            std::string::npos);
  EXPECT_THROW(ConfigReader::from_string("- 1\n- 2\n", "list.yaml"), ConfigError);
}

TEST(ConfigReader, AKeyWrittenTwiceIsAnErrorNamingBothLines) {
  // yaml-cpp keeps both, and a lookup finds one: the other value was dropped without a word.
  EXPECT_EQ(message_of([] {
              ConfigReader::from_string("a: 1\nsection:\n  x: 2\n  y: 3\n  x: 4\n", "dup.yaml");
            }),
            "dup.yaml:5: key 'x' appears twice in the same map (first on line 3)");
  EXPECT_EQ(message_of([] { ConfigReader::from_string("{a: 1, b: 2, a: 3}", "flow.yaml"); }),
            "flow.yaml:1: key 'a' appears twice in the same map (first on line 1)");
  // The same key in two maps is two keys.
  EXPECT_EQ(message_of([] { ConfigReader::from_string("a: {x: 1}\nb: {x: 2}\n", "ok.yaml"); }),
            "(no ConfigError)");
}

TEST(ConfigReader, KeysThatAreNotTextAndAliasesAreErrors) {
  EXPECT_NE(message_of([] {
              ConfigReader::from_string("? [a, b]\n: 1\n", "k.yaml");
            }).find("k.yaml:1: a key must be a name, not a list or a map"),
            std::string::npos);
  // Aliases could nest into billions of keys; a configuration needs none.
  EXPECT_NE(message_of([] {
              ConfigReader::from_string("a: &x 1\nb: *x\n", "alias.yaml");
            }).find("alias.yaml:2: aliases"),
            std::string::npos);
}

TEST(ConfigReader, ReadsFromAFile) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "omninav_config_test.yaml";
  std::ofstream(file) << "width_px: 1080\n";
  int width = 0;
  const ConfigReader config = ConfigReader::from_file(file);
  config.read("width_px", width, 1, 5000);
  EXPECT_EQ(width, 1080);
  EXPECT_EQ(config.source_name(), file.string());
  std::filesystem::remove(file);
}

TEST(ConfigReader, NonFiniteNumbersAreRefusedWhateverTheRange) {
  for (const std::string value : {".nan", ".inf", "-.inf", "nan", "1e999"}) {
    const ConfigReader config = ConfigReader::from_string("a: " + value + "\n", "n.yaml");
    double a = 1.0;
    std::optional<double> b;
    EXPECT_NE(
        message_of([&] { config.read("a", a, -1e300, 1e300); }).find("key 'a' must be a number"),
        std::string::npos)
        << value;
    EXPECT_EQ(a, 1.0);
    EXPECT_NE(message_of([&] { config.read("a", b, 0.0, 1.0); }), "(no ConfigError)") << value;
  }
}

}  // namespace
}  // namespace omninav
