#include "omninav/io/folder_sequence.hpp"

#include <gtest/gtest.h>

#include "io_test_support.hpp"
#include "omninav/core/errors.hpp"
#include "support/shared_data.hpp"

namespace omninav::io {
namespace {

using testing::make_image;
using testing::same_pixels;
using testing::TempDir;
using testing::write_image;
using testing::write_text;

TEST(FolderSequence, ReadsImagesInNaturalOrder) {
  const TempDir dir;
  // Written out of order, with the frame index in the pixels and the name.
  for (int index : {10, 2, 1, 0, 11}) {
    write_image(dir / ("img" + std::to_string(index) + ".png"), make_image(index));
  }
  write_text(dir / "notes.txt", "not an image");
  write_text(dir / "._img3.png", "a hidden resource fork, not an image");

  FolderSequence sequence(dir.path());
  ASSERT_EQ(sequence.size(), 5u);
  const std::vector<int> expected = {0, 1, 2, 10, 11};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    std::optional<Frame> frame = sequence.next();
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->index, static_cast<int>(i));
    EXPECT_TRUE(same_pixels(frame->image, make_image(expected[i]))) << "frame " << i;
    EXPECT_EQ(frame->source, (dir / ("img" + std::to_string(expected[i]) + ".png")).string());
    EXPECT_FALSE(frame->time_s);
    EXPECT_FALSE(frame->truth);
  }
  EXPECT_FALSE(sequence.next());
  EXPECT_FALSE(sequence.next());  // stays at the end
}

TEST(FolderSequence, AcceptsEveryImageExtensionInAnyCase) {
  const TempDir dir;
  write_image(dir / "a1.PNG", make_image(1));
  write_image(dir / "a2.bmp", make_image(2));
  write_image(dir / "a3.tiff", make_image(3));
  write_image(dir / "a4.ppm", make_image(4));
  EXPECT_EQ(list_images(dir.path()).size(), 4u);
}

TEST(FolderSequence, GreyImagesComeBackAsBgr) {
  const TempDir dir;
  write_image(dir / "grey.pgm", cv::Mat(8, 36, CV_8UC1, cv::Scalar(77)));
  FolderSequence sequence(dir.path());
  const std::optional<Frame> frame = sequence.next();
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->image.type(), CV_8UC3);
  EXPECT_EQ(frame->image.at<cv::Vec3b>(3, 5), cv::Vec3b(77, 77, 77));
}

TEST(FolderSequence, EmptyFolderIsInputErrorNamingIt) {
  const TempDir dir;
  write_text(dir / "readme.txt", "no images here");
  EXPECT_INPUT_ERROR(FolderSequence{dir.path()}, dir.path().string(), "no images");
}

TEST(FolderSequence, CorruptImageIsInputErrorNamingIt) {
  const TempDir dir;
  write_image(dir / "a1.png", make_image(1));
  write_text(dir / "x.png", "garbage bytes, not a PNG");
  FolderSequence sequence(dir.path());
  ASSERT_TRUE(sequence.next());
  EXPECT_INPUT_ERROR(sequence.next(), (dir / "x.png").string());
}

TEST(FolderSequence, MixedSizesNameTheFileAndBothSizes) {
  const TempDir dir;
  write_image(dir / "a1.png", make_image(1));
  write_image(dir / "a2.png", make_image(2, {40, 8}));
  FolderSequence sequence(dir.path());
  ASSERT_TRUE(sequence.next());
  EXPECT_INPUT_ERROR(sequence.next(), (dir / "a2.png").string(), "40x8", "36x8");
}

TEST(FolderSequence, DescribesFolderAndCount) {
  const TempDir dir;
  write_image(dir / "a1.png", make_image(1));
  const FolderSequence sequence(dir.path());
  EXPECT_NE(sequence.describe().find(dir.path().string()), std::string::npos);
  EXPECT_NE(sequence.describe().find("1 images"), std::string::npos);
}

TEST(FolderSequence, ReadsRealFtlArenaRoute) {
  OMNINAV_REQUIRE_SHARED_DATA("real/ftl-arena/route");
  const std::filesystem::path folder = omninav::testing::shared_data_dir() / "real/ftl-arena/route";
  FolderSequence sequence(folder);
  ASSERT_EQ(sequence.size(), 130u);
  std::vector<std::string> names;
  while (std::optional<Frame> frame = sequence.next()) {
    EXPECT_EQ(frame->image.size(), cv::Size(180, 50)) << frame->source;
    EXPECT_EQ(frame->image.type(), CV_8UC3);
    names.push_back(std::filesystem::path(frame->source).filename().string());
  }
  ASSERT_EQ(names.size(), 130u);
  EXPECT_EQ(names[0], "snapshot_0.png");
  EXPECT_EQ(names[2], "snapshot_2.png");
  EXPECT_EQ(names[10], "snapshot_10.png");
  EXPECT_EQ(names[129], "snapshot_129.png");
}

}  // namespace
}  // namespace omninav::io
