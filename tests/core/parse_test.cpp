#include "omninav/core/parse.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "omninav/core/errors.hpp"

namespace omninav {
namespace {

TEST(Parse, NumbersWithBlanks) {
  EXPECT_DOUBLE_EQ(parse_double(" 12.5 ", "f:1"), 12.5);
  EXPECT_DOUBLE_EQ(parse_double("-3e2", "f:1"), -300.0);
  EXPECT_EQ(parse_int(" 42\r", "f:1"), 42);
}

TEST(Parse, GarbageNamesWhere) {
  try {
    parse_double("12abc", "entries.csv:7");
    FAIL();
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(), "entries.csv:7: '12abc' is not a number");
  }
  EXPECT_THROW(parse_double("", "x"), InputError);
  EXPECT_THROW(parse_double("nan", "x"), InputError);
  EXPECT_THROW(parse_int("4.5", "x"), InputError);
}

TEST(Parse, CoordinatesBeyondTenThousandKilometresAreRefused) {
  EXPECT_DOUBLE_EQ(check_coordinate_m(-1e7, "x"), -1e7);
  EXPECT_DOUBLE_EQ(check_coordinate_m(12.5, "x"), 12.5);
  try {
    check_coordinate_m(1e157, "entries.csv:3: column 'X [mm]'");  // 1e160 mm
    FAIL();
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(),
                 "entries.csv:3: column 'X [mm]': 1e+157 m is not a position (beyond ±1e+07 m)");
  }
  EXPECT_THROW(check_coordinate_m(std::numeric_limits<double>::infinity(), "x"), InputError);
  EXPECT_THROW(check_coordinate_m(std::numeric_limits<double>::quiet_NaN(), "x"), InputError);
}

TEST(Split, KeepsEmptyFieldsAndTrims) {
  const std::vector<std::string> fields = split(" a, b ,,c ", ',');
  ASSERT_EQ(fields.size(), 4u);
  EXPECT_EQ(fields[0], "a");
  EXPECT_EQ(fields[1], "b");
  EXPECT_EQ(fields[2], "");
  EXPECT_EQ(fields[3], "c");
}

TEST(CheckPose, EveryCoordinateWithinTheBoundAndEveryAngleFinite) {
  EXPECT_NO_THROW(check_pose({1.0, -2.0, 0.5, 3.0, 0.1, -0.1}, "pose"));
  const auto message = [](const CameraPose& pose) {
    try {
      check_pose(pose, "run.bag#/odom message 3");
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  EXPECT_EQ(message({1e300, 0, 0, 0, 0, 0}),
            "run.bag#/odom message 3: x: 1e+300 m is not a position (beyond ±1e+07 m)");
  EXPECT_NE(message({0, std::nan(""), 0, 0, 0, 0}).find("y: nan m"), std::string::npos);
  EXPECT_NE(message({0, 0, -INFINITY, 0, 0, 0}).find("z: -inf m"), std::string::npos);
  EXPECT_EQ(message({0, 0, 0, std::nan(""), 0, 0}),
            "run.bag#/odom message 3: heading is nan, not a finite angle");
}

}  // namespace
}  // namespace omninav
