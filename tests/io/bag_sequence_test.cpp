#include "omninav/io/bag_sequence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "io_test_support.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::io {
namespace {

StampedPose yawed(double stamp_s, double x_m, double y_m, double yaw_rad) {
  StampedPose pose;
  pose.stamp_s = stamp_s;
  pose.x_m = x_m;
  pose.y_m = y_m;
  pose.qz = std::sin(yaw_rad / 2.0);
  pose.qw = std::cos(yaw_rad / 2.0);
  return pose;
}

constexpr double kPi = std::numbers::pi;

TEST(InterpolatePose, PositionLinearAndYawAlongTheShorterArc) {
  // 170 degrees to -170 degrees: 20 degrees through 180, not 340 through 0.
  const std::vector<StampedPose> poses = {yawed(10.0, 0.0, 0.0, 170.0 * kPi / 180.0),
                                          yawed(12.0, 2.0, -4.0, -170.0 * kPi / 180.0)};
  const std::optional<CameraPose> middle = interpolate_pose(poses, 11.0);
  ASSERT_TRUE(middle.has_value());
  EXPECT_NEAR(middle->x_m, 1.0, 1e-12);
  EXPECT_NEAR(middle->y_m, -2.0, 1e-12);
  EXPECT_NEAR(std::abs(middle->heading_rad), kPi, 1e-9);
  const std::optional<CameraPose> quarter = interpolate_pose(poses, 10.5);
  ASSERT_TRUE(quarter.has_value());
  EXPECT_NEAR(quarter->x_m, 0.5, 1e-12);
  EXPECT_NEAR(quarter->heading_rad, 175.0 * kPi / 180.0, 1e-9);
}

TEST(InterpolatePose, ExactStampsGiveThePoseAndNothingOutsideTheRange) {
  const std::vector<StampedPose> poses = {yawed(1.0, 1.0, 2.0, 0.5), yawed(2.0, 3.0, 2.0, 1.0),
                                          yawed(3.0, 3.0, 5.0, -1.0)};
  const std::optional<CameraPose> second = interpolate_pose(poses, 2.0);
  ASSERT_TRUE(second.has_value());
  EXPECT_DOUBLE_EQ(second->x_m, 3.0);
  EXPECT_NEAR(second->heading_rad, 1.0, 1e-12);
  const std::optional<CameraPose> first = interpolate_pose(poses, 1.0);
  ASSERT_TRUE(first.has_value());
  EXPECT_NEAR(first->heading_rad, 0.5, 1e-12);
  EXPECT_FALSE(interpolate_pose(poses, 0.999).has_value());
  EXPECT_FALSE(interpolate_pose(poses, 3.001).has_value());
  EXPECT_FALSE(interpolate_pose({}, 1.0).has_value());
}

TEST(IsBag, ByExtensionOrRos2Folder) {
  const testing::TempDir dir;
  EXPECT_TRUE(is_bag("run.bag"));
  EXPECT_TRUE(is_bag("run.MCAP"));
  EXPECT_TRUE(is_bag("run_0.db3"));
  EXPECT_FALSE(is_bag("run.mp4"));
  EXPECT_FALSE(is_bag(dir.path()));
  testing::write_text(dir / "metadata.yaml", "rosbag2_bagfile_information: {}\n");
  EXPECT_TRUE(is_bag(dir.path()));
}

TEST(OpenSequence, TopicsForAnInputThatIsNoBagAreAUsageError) {
  const testing::TempDir dir;
  testing::write_image(dir / "0.png", testing::make_image(0));
  EXPECT_THROW(open_sequence(dir.path(), {.topic = "/camera", .pose_topic = ""}), UsageError);
  EXPECT_THROW(open_sequence(dir.path(), {.topic = "", .pose_topic = "/odom"}), UsageError);
  EXPECT_EQ(open_sequence(dir.path(), {})->size(), 1u);
}

TEST(OpenBag, FilesThatAreNotBagsAreClearErrors) {
  const testing::TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"run.bag", "ROS 1 bag"}, {"run.mcap", "not an MCAP file"}, {"run.db3", "ROS 2 SQLite bag"}};
  for (const auto& [name, what] : cases) {
    testing::write_text(dir / name, "PK\x03\x04 a zip file, long enough to look like anything");
    EXPECT_INPUT_ERROR(open_bag(dir / name, {}), name, what);
  }
  EXPECT_INPUT_ERROR(open_bag(dir / "none.mcap", {}), "none.mcap", "no such bag");
}

}  // namespace
}  // namespace omninav::io
