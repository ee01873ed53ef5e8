#include "omninav/io/csv_sequence.hpp"

#include <gtest/gtest.h>

#include "io_test_support.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::io {
namespace {

using testing::index_of;
using testing::make_image;
using testing::TempDir;
using testing::write_image;
using testing::write_text;

// Parsed doubles are the nearest to their decimal text, as are the expected literals below.
constexpr double kExact = 1e-12;

TEST(CsvSequence, ReadsPosesAndImagesRelativeToTheCsvFolder) {
  const TempDir dir;
  std::filesystem::create_directories(dir / "images");
  write_image(dir / "images/b.png", make_image(5));
  write_image(dir / "images/a.png", make_image(6));
  // Columns in an unusual order, an extra column, Windows line ends: rows keep the file order.
  write_text(dir / "poses.csv",
             "heading_deg, note, file, y_m, x_m\r\n"
             "90, first, images/b.png, 2.5, -1.25\r\n"
             "\r\n"
             "-45.5, second, images/a.png, 0, 3\r\n");

  CsvSequence sequence(dir / "poses.csv");
  ASSERT_EQ(sequence.size(), 2u);

  const std::optional<Frame> first = sequence.next();
  ASSERT_TRUE(first);
  EXPECT_EQ(first->index, 0);
  EXPECT_EQ(index_of(first->image), 5);
  EXPECT_EQ(first->source, (dir / "images/b.png").string());
  ASSERT_TRUE(first->truth);
  EXPECT_NEAR(first->truth->x_m, -1.25, kExact);
  EXPECT_NEAR(first->truth->y_m, 2.5, kExact);
  EXPECT_NEAR(first->truth->z_m, 0.0, kExact);
  EXPECT_NEAR(first->truth->heading_rad, kPi / 2.0, kExact);
  EXPECT_FALSE(first->time_s);

  const std::optional<Frame> second = sequence.next();
  ASSERT_TRUE(second);
  EXPECT_EQ(index_of(second->image), 6);
  EXPECT_NEAR(second->truth->heading_rad, deg_to_rad(-45.5), kExact);
  EXPECT_FALSE(sequence.next());
}

TEST(CsvSequence, ReadsOptionalTimeAndHeight) {
  const TempDir dir;
  write_image(dir / "a.png", make_image(1));
  write_text(dir / "poses.csv", "file,x_m,y_m,heading_deg,time_s,z_m\na.png,1,2,3,12.75,0.3\n");
  CsvSequence sequence(dir / "poses.csv");
  const std::optional<Frame> frame = sequence.next();
  ASSERT_TRUE(frame && frame->time_s && frame->truth);
  EXPECT_NEAR(*frame->time_s, 12.75, kExact);
  EXPECT_NEAR(frame->truth->z_m, 0.3, kExact);
}

TEST(CsvSequence, MissingColumnIsInputErrorNamingFileAndColumn) {
  const TempDir dir;
  write_image(dir / "a.png", make_image(1));
  write_text(dir / "poses.csv", "file,x_m,heading_deg\na.png,1,3\n");
  EXPECT_INPUT_ERROR(CsvSequence{dir / "poses.csv"}, (dir / "poses.csv").string(),
                     "missing column 'y_m'");
}

TEST(CsvSequence, NonNumericFieldIsInputErrorNamingFileAndLine) {
  const TempDir dir;
  write_image(dir / "a.png", make_image(1));
  write_text(dir / "poses.csv", "file,x_m,y_m,heading_deg\na.png,1,2,3\na.png,1,two,3\n");
  EXPECT_INPUT_ERROR(CsvSequence{dir / "poses.csv"}, (dir / "poses.csv").string() + ":3", "'y_m'",
                     "'two'");
}

TEST(CsvSequence, NonFiniteOrAbsurdPositionIsInputErrorNamingFileAndLine) {
  const TempDir dir;
  write_image(dir / "a.png", make_image(1));
  write_text(dir / "poses.csv", "file,x_m,y_m,heading_deg\na.png,1,2,3\na.png,1e157,2,3\n");
  EXPECT_INPUT_ERROR(CsvSequence{dir / "poses.csv"}, (dir / "poses.csv").string() + ":3", "'x_m'",
                     "not a position");
  for (const std::string bad : {"nan", "inf", "-inf"}) {
    write_text(dir / "poses.csv", "file,x_m,y_m,heading_deg\na.png,1," + bad + ",3\n");
    EXPECT_INPUT_ERROR(CsvSequence{dir / "poses.csv"}, (dir / "poses.csv").string() + ":2",
                       "'y_m'");
  }
}

TEST(CsvSequence, MissingImageIsInputErrorNamingImageAndLine) {
  const TempDir dir;
  write_image(dir / "a.png", make_image(1));
  write_text(dir / "poses.csv", "file,x_m,y_m,heading_deg\na.png,1,2,3\n\nb.png,1,2,3\n");
  EXPECT_INPUT_ERROR(CsvSequence{dir / "poses.csv"}, (dir / "poses.csv").string() + ":4", "b.png");
}

TEST(CsvSequence, RowWithTooFewFieldsIsInputErrorNamingLine) {
  const TempDir dir;
  write_image(dir / "a.png", make_image(1));
  write_text(dir / "poses.csv", "file,x_m,y_m,heading_deg\na.png,1,2\n");
  EXPECT_INPUT_ERROR(CsvSequence{dir / "poses.csv"}, (dir / "poses.csv").string() + ":2",
                     "3 fields");
}

TEST(CsvSequence, HeaderOnlyIsInputError) {
  const TempDir dir;
  write_text(dir / "poses.csv", "file,x_m,y_m,heading_deg\n");
  EXPECT_INPUT_ERROR(CsvSequence{dir / "poses.csv"}, (dir / "poses.csv").string());
}

TEST(CsvSequence, CorruptImageIsInputErrorNamingIt) {
  const TempDir dir;
  write_text(dir / "x.png", "garbage");
  write_text(dir / "poses.csv", "file,x_m,y_m,heading_deg\nx.png,1,2,3\n");
  CsvSequence sequence(dir / "poses.csv");
  EXPECT_INPUT_ERROR(sequence.next(), (dir / "x.png").string());
}

TEST(CsvSequence, MixedSizesNameTheFileAndBothSizes) {
  const TempDir dir;
  write_image(dir / "a.png", make_image(1));
  write_image(dir / "b.png", make_image(2, {36, 9}));
  write_text(dir / "poses.csv", "file,x_m,y_m,heading_deg\na.png,1,2,3\nb.png,1,2,3\n");
  CsvSequence sequence(dir / "poses.csv");
  ASSERT_TRUE(sequence.next());
  EXPECT_INPUT_ERROR(sequence.next(), (dir / "b.png").string(), "36x9", "36x8");
}

}  // namespace
}  // namespace omninav::io
