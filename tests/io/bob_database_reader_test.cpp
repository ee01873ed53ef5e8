// BobDatabaseReader on databases written by hand in BoB's format. The first two are BoB's own
// examples (bob_robotics, docs_source/example_image_databases/example_route and example_grid,
// made by its ant_world_db_creator), with small generated images in place of the renders.

#include <gtest/gtest.h>

#include <opencv2/videoio.hpp>

#include "io_test_support.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/io/bob_database.hpp"

namespace omninav::io {
namespace {

using testing::index_of;
using testing::make_image;
using testing::TempDir;
using testing::write_image;
using testing::write_text;

// Parsed doubles are the nearest to their decimal text, as are the expected values below.
constexpr double kExact = 1e-12;

const char* const kExampleRouteMetadata =
    "%YAML:1.0\n---\nmetadata:\n   time: \"2019-01-29 13:07:15\"\n   type: route\n"
    "   camera:\n      name: opengl\n      resolution: [ 720, 150 ]\n      isPanoramic: 0\n"
    "   needsUnwrapping: 0\n   isGreyscale: 0\n";
const char* const kExampleRouteEntries =
    "X [mm], Y [mm], Z [mm], Heading [degrees], Filename\n"
    "6300, 8450, 10, 219.962, image_00000.png\n"
    "6293.58, 8442.34, 10, 219.962, image_00001.png\n"
    "6287.26, 8434.58, 10, 219.159, image_00002.png\n";

// The resolution the examples' metadata states, which their images must have.
const cv::Size kExampleSize(720, 150);

void write_example_route(const TempDir& dir) {
  write_text(dir / kBobMetadataFile, kExampleRouteMetadata);
  write_text(dir / kBobEntriesFile, kExampleRouteEntries);
  for (int i = 0; i < 3; ++i)
    write_image(dir / ("image_0000" + std::to_string(i) + ".png"), make_image(i, kExampleSize));
}

TEST(BobDatabaseReader, ReadsBobExampleRoute) {
  const TempDir dir;
  write_example_route(dir);

  BobDatabaseReader reader(dir.path());
  EXPECT_FALSE(reader.info().is_grid);
  EXPECT_EQ(reader.info().camera_name, "opengl");
  EXPECT_EQ(reader.info().image_size, cv::Size(720, 150));
  ASSERT_TRUE(reader.info().needs_unwrapping);
  EXPECT_FALSE(*reader.info().needs_unwrapping);
  EXPECT_FALSE(reader.info().frame_rate_hz);
  ASSERT_EQ(reader.size(), 3u);
  EXPECT_EQ(reader.entries()[1].csv_line, 3);
  EXPECT_FALSE(reader.entries()[1].grid);

  const std::vector<Frame> frames = read_all(reader);
  ASSERT_EQ(frames.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(frames[i].index, i);
    EXPECT_EQ(index_of(frames[i].image), i);
    EXPECT_FALSE(frames[i].time_s);
    ASSERT_TRUE(frames[i].truth);
  }
  // mm to m, degrees to radians, z included; no pitch or roll columns: level.
  const CameraPose& pose = *frames[1].truth;
  EXPECT_NEAR(pose.x_m, 6.29358, kExact);
  EXPECT_NEAR(pose.y_m, 8.44234, kExact);
  EXPECT_NEAR(pose.z_m, 0.010, kExact);
  EXPECT_NEAR(pose.heading_rad, deg_to_rad(219.962), kExact);
  EXPECT_EQ(pose.pitch_rad, 0.0);
  EXPECT_EQ(pose.roll_rad, 0.0);
  EXPECT_EQ(frames[2].source, (dir / "image_00002.png").string());
}

TEST(BobDatabaseReader, ReadsBobExampleGrid) {
  const TempDir dir;
  write_text(
      dir / kBobMetadataFile,
      "%YAML:1.0\n---\nmetadata:\n   time: \"2019-01-29 13:05:14\"\n   type: grid\n"
      "   grid:\n      beginAtMM: [ 0., 0., 10. ]\n      separationMM: [ 1000., 1000., 0. ]\n"
      "      size: [ 2, 2, 1 ]\n   camera:\n      name: opengl\n"
      "      resolution: [ 720, 150 ]\n      isPanoramic: 0\n   needsUnwrapping: 0\n"
      "   isGreyscale: 0\n");
  write_text(dir / kBobEntriesFile,
             "X [mm], Y [mm], Z [mm], Heading [degrees], Filename, Grid X, Grid Y, Grid Z\n"
             "0, 0, 10, 0, image_+000000_+000000_+000010.png, 0, 0, 0\n"
             "1000, 0, 10, 0, image_+001000_+000000_+000010.png, 1, 0, 0\n"
             "0, 1000, 10, 0, image_+000000_+001000_+000010.png, 0, 1, 0\n"
             "1000, 1000, 10, 0, image_+001000_+001000_+000010.png, 1, 1, 0\n");
  write_image(dir / "image_+000000_+000000_+000010.png", make_image(0, kExampleSize));
  write_image(dir / "image_+001000_+000000_+000010.png", make_image(1, kExampleSize));
  write_image(dir / "image_+000000_+001000_+000010.png", make_image(2, kExampleSize));
  write_image(dir / "image_+001000_+001000_+000010.png", make_image(3, kExampleSize));

  BobDatabaseReader reader(dir.path());
  EXPECT_TRUE(reader.info().is_grid);
  ASSERT_EQ(reader.entries().size(), 4u);
  EXPECT_EQ(reader.entries()[2].grid, (std::array{0, 1, 0}));
  EXPECT_EQ(reader.entries()[3].grid, (std::array{1, 1, 0}));
  // The grid's geometry as GridRecorder states it; the spacing is the smallest positive
  // separation in the floor's plane.
  ASSERT_TRUE(reader.info().grid);
  EXPECT_EQ(reader.info().grid->begin_mm, (std::array{0.0, 0.0, 10.0}));
  EXPECT_EQ(reader.info().grid->separation_mm, (std::array{1000.0, 1000.0, 0.0}));
  EXPECT_EQ(reader.info().grid->size, (std::array{2, 2, 1}));
  EXPECT_EQ(reader.grid_spacing_m(), std::optional<double>(1.0));
  ASSERT_TRUE(reader.entries()[1].truth);
  EXPECT_NEAR(reader.entries()[1].truth->x_m, 1.0, kExact);
  const std::vector<Frame> frames = read_all(reader);
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_EQ(index_of(frames[3].image), 3);
}

TEST(BobDatabaseReader, GridSpacingIsTheSmallestPositiveSeparation) {
  GridGeometry grid;
  EXPECT_FALSE(grid.spacing_m());  // no separation stated
  grid.separation_mm = {300.0, 250.0, 100.0};
  EXPECT_DOUBLE_EQ(*grid.spacing_m(), 0.25);  // z is a grid's height, not a floor spacing
  grid.separation_mm = {0.0, 0.0, 100.0};
  EXPECT_DOUBLE_EQ(*grid.spacing_m(), 0.1);  // a column of points
}

// A grid database of one image, a.png, at the origin with these grid indices.
void write_one_grid_image(const TempDir& dir, const std::string& indices) {
  write_text(dir / kBobEntriesFile,
             "X [mm], Y [mm], Z [mm], Heading [degrees], Filename, Grid X, Grid Y, Grid Z\n"
             "0, 0, 0, 0, a.png, " +
                 indices + "\n");
  write_image(dir / "a.png", make_image(0));
}

TEST(BobDatabaseReader, BadGridSeparationIsInputErrorNamingMetadata) {
  const TempDir dir;
  write_one_grid_image(dir, "0, 0, 0");
  for (const char* separation : {"[ -300., 300., 0. ]", "[ 300., 300. ]", "300", "[ a, 1, 2 ]"}) {
    write_text(
        dir / kBobMetadataFile,
        std::string("metadata:\n  type: grid\n  grid:\n    separationMM: ") + separation + "\n");
    EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobMetadataFile).string(),
                       "metadata.grid.separationMM is not [x, y, z]");
  }
  write_text(dir / kBobMetadataFile, "metadata:\n  type: grid\n  grid: 300\n");
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobMetadataFile).string(),
                     "metadata.grid is not a map");
}

TEST(BobDatabaseReader, WithoutMetadataGridColumnsMakeAGrid) {
  const TempDir dir;
  write_one_grid_image(dir, "4, 5, 6");
  const BobDatabaseReader reader(dir.path());
  EXPECT_TRUE(reader.info().is_grid);
  EXPECT_EQ(reader.entries()[0].grid, (std::array{4, 5, 6}));
}

TEST(BobDatabaseReader, ReadsColumnsByNameWithExtrasPitchRollAndTimestamp) {
  const TempDir dir;
  // Column order and extra fields as BoB's data-collection programs write them.
  write_text(dir / kBobEntriesFile,
             "Timestamp [ms],X [mm],Y [mm],Z [mm],Heading [degrees],Pitch [degrees],"
             "Roll [degrees],Speed,Filename,GPS quality\n"
             "56.115072,2260.25,127.636,87.2295,87.4229,1.5,-2.25,0.3,image0.jpg,4\n"
             "156.293440,2237.22,127.445,88.0277,87.4621,nan,nan,0.3,image1.jpg,4\n");
  write_image(dir / "image0.jpg", make_image(0));
  write_image(dir / "image1.jpg", make_image(1));
  write_text(dir / kBobMetadataFile,
             "%YAML:1.0\n---\nmetadata:\n   type: route\n   frameRate: 15.\n");

  BobDatabaseReader reader(dir.path());
  ASSERT_TRUE(reader.info().frame_rate_hz);
  EXPECT_EQ(*reader.info().frame_rate_hz, 15.0);
  const std::vector<Frame> frames = read_all(reader);
  ASSERT_EQ(frames.size(), 2u);
  // The recorder's own timestamps beat the nominal frame rate.
  ASSERT_TRUE(frames[0].time_s && frames[1].time_s);
  EXPECT_NEAR(*frames[0].time_s, 0.056115072, kExact);
  EXPECT_NEAR(*frames[1].time_s, 0.156293440, kExact);
  ASSERT_TRUE(frames[0].truth && frames[1].truth);
  EXPECT_NEAR(frames[0].truth->x_m, 2.26025, kExact);
  EXPECT_NEAR(frames[0].truth->z_m, 0.0872295, kExact);
  EXPECT_NEAR(frames[0].truth->pitch_rad, deg_to_rad(1.5), kExact);
  EXPECT_NEAR(frames[0].truth->roll_rad, deg_to_rad(-2.25), kExact);
  // NaN pitch and roll: not measured, a level camera.
  EXPECT_EQ(frames[1].truth->pitch_rad, 0.0);
  EXPECT_EQ(frames[1].truth->roll_rad, 0.0);
}

TEST(BobDatabaseReader, FrameRateGivesTimesWithoutTimestampColumn) {
  const TempDir dir;
  write_example_route(dir);
  write_text(dir / kBobMetadataFile,
             "%YAML:1.0\n---\nmetadata:\n   type: route\n   frameRate: 4.\n");
  BobDatabaseReader reader(dir.path());
  const std::vector<Frame> frames = read_all(reader);
  ASSERT_EQ(frames.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(frames[i].time_s);
    EXPECT_DOUBLE_EQ(*frames[i].time_s, i / 4.0);
  }
}

TEST(BobDatabaseReader, ReadsMetadataWithoutYamlDirective) {
  const TempDir dir;
  write_example_route(dir);
  // BoB's reader prepends the directive itself, so files without it are valid BoB metadata.
  write_text(dir / kBobMetadataFile,
             "metadata:\n  type: route\n  camera:\n    name: pixpro_usb\n"
             "    resolution: [1440, 1440]\n    isPanoramic: 1\n");
  const BobDatabaseReader reader(dir.path());
  EXPECT_EQ(reader.info().camera_name, "pixpro_usb");
  // needsUnwrapping absent: BoB takes camera.isPanoramic instead.
  ASSERT_TRUE(reader.info().needs_unwrapping);
  EXPECT_TRUE(*reader.info().needs_unwrapping);
}

TEST(BobDatabaseReader, NanOrEmptyPositionMeansNoTruth) {
  const TempDir dir;
  write_text(dir / kBobEntriesFile,
             "X [mm], Y [mm], Z [mm], Heading [degrees], Filename\n"
             "1, 2, 3, 4, a.png\n"
             "nan, nan, nan, 4, a.png\n"
             ", 2, 3, 4, a.png\n");
  write_image(dir / "a.png", make_image(0));
  const BobDatabaseReader reader(dir.path());
  ASSERT_EQ(reader.entries().size(), 3u);
  EXPECT_TRUE(reader.entries()[0].truth);
  EXPECT_FALSE(reader.entries()[1].truth);
  EXPECT_FALSE(reader.entries()[2].truth);
  EXPECT_NE(reader.describe().find("1 with poses"), std::string::npos) << reader.describe();
}

TEST(BobDatabaseReader, ReadsVideoDatabase) {
  const TempDir dir;
  const cv::Size size{64, 16};
  {
    cv::VideoWriter writer((dir / "route.avi").string(),
                           cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 15.0, size);
    if (!writer.isOpened()) GTEST_SKIP() << "cv::VideoWriter cannot write MJPG in AVI here";
    for (int i = 0; i < 3; ++i) writer.write(cv::Mat(size, CV_8UC3, cv::Scalar::all(20 + 80 * i)));
  }
  // As BoB's video recorders write them: no Filename column, a Frame column of camera frame
  // numbers, and the video named in the metadata.
  write_text(dir / kBobMetadataFile,
             "%YAML:1.0\n---\nmetadata:\n   type: route\n"
             "   videoFile: \"route.avi\"\n   frameRate: 15.\n");
  write_text(dir / kBobEntriesFile,
             "X [mm], Y [mm], Z [mm], Heading [degrees], Frame\n"
             "0, 0, 0, 0, 770714\n100, 0, 0, 0, 770724\n200, 0, 0, 0, 770735\n");

  BobDatabaseReader reader(dir.path());
  const std::vector<Frame> frames = read_all(reader);
  ASSERT_EQ(frames.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(cv::mean(frames[i].image)[0], 20 + 80 * i, 4.0);  // MJPEG: a few levels off
    EXPECT_EQ(frames[i].source, (dir / "route.avi").string() + "#frame " + std::to_string(i));
    ASSERT_TRUE(frames[i].truth && frames[i].time_s);
    EXPECT_NEAR(frames[i].truth->x_m, 0.1 * i, kExact);
    EXPECT_DOUBLE_EQ(*frames[i].time_s, i / 15.0);
  }

  // A video shorter than its entries is an error, not a silent truncation.
  write_text(dir / kBobEntriesFile,
             "X [mm], Y [mm], Z [mm], Heading [degrees]\n0,0,0,0\n0,0,0,0\n0,0,0,0\n0,0,0,0\n");
  BobDatabaseReader longer(dir.path());
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(longer.next());
  EXPECT_INPUT_ERROR(longer.next(), dir.path().string(), "3 frames", "4 entries");
}

// Bad input: each case names the file, and the line for CSV rows.

TEST(BobDatabaseReader, MissingColumnIsInputErrorNamingFileAndColumn) {
  const TempDir dir;
  write_text(dir / kBobEntriesFile, "X [mm], Y [mm], Z [mm], Filename\n1, 2, 3, a.png\n");
  write_image(dir / "a.png", make_image(0));
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobEntriesFile).string(),
                     "missing column 'Heading [degrees]'");
}

TEST(BobDatabaseReader, GridTypeWithoutGridColumnsIsInputError) {
  const TempDir dir;
  write_example_route(dir);
  write_text(dir / kBobMetadataFile, "%YAML:1.0\n---\nmetadata:\n   type: grid\n");
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobEntriesFile).string(),
                     "missing column 'Grid X'");
}

TEST(BobDatabaseReader, NonNumericFieldIsInputErrorNamingFileAndLine) {
  const TempDir dir;
  write_example_route(dir);
  write_text(dir / kBobEntriesFile,
             "X [mm], Y [mm], Z [mm], Heading [degrees], Filename\n"
             "6300, 8450, 10, 219.962, image_00000.png\n"
             "6293.58, north, 10, 219.962, image_00001.png\n");
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobEntriesFile).string() + ":3",
                     "'Y [mm]'", "'north'");
}

TEST(BobDatabaseReader, NegativeGridIndexIsInputErrorNamingLine) {
  const TempDir dir;
  write_text(dir / kBobEntriesFile,
             "X [mm], Y [mm], Z [mm], Heading [degrees], Filename, Grid X, Grid Y, Grid Z\n"
             "0, 0, 0, 0, a.png, 0, -1, 0\n");
  write_image(dir / "a.png", make_image(0));
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobEntriesFile).string() + ":2",
                     "'Grid Y'");
}

TEST(BobDatabaseReader, EntryWithMissingImageIsInputErrorNamingImageAndLine) {
  const TempDir dir;
  write_example_route(dir);
  std::filesystem::remove(dir / "image_00002.png");
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobEntriesFile).string() + ":4",
                     "image_00002.png");
}

TEST(BobDatabaseReader, CorruptImageIsInputErrorNamingIt) {
  const TempDir dir;
  write_example_route(dir);
  write_text(dir / "image_00001.png", "garbage, not a PNG");
  BobDatabaseReader reader(dir.path());
  ASSERT_TRUE(reader.next());
  EXPECT_INPUT_ERROR(reader.next(), (dir / "image_00001.png").string());
}

TEST(BobDatabaseReader, MixedSizesNameTheFileAndBothSizes) {
  const TempDir dir;
  write_example_route(dir);
  std::filesystem::remove(dir / kBobMetadataFile);  // no stated resolution: the first image's
  write_image(dir / "image_00001.png", make_image(1, {72, 16}));
  BobDatabaseReader reader(dir.path());
  ASSERT_TRUE(reader.next());
  EXPECT_INPUT_ERROR(reader.next(), (dir / "image_00001.png").string(), "72x16", "720x150");
}

TEST(BobDatabaseReader, ImagesOfAnotherSizeThanTheMetadataStatesAreInputErrors) {
  const TempDir dir;
  write_example_route(dir);
  for (int i = 0; i < 3; ++i) {
    write_image(dir / ("image_0000" + std::to_string(i) + ".png"), make_image(i, {36, 8}));
  }
  BobDatabaseReader reader(dir.path());
  EXPECT_INPUT_ERROR(reader.next(), (dir / "image_00000.png").string(), "36x8",
                     (dir / kBobMetadataFile).string(), "camera.resolution is [720, 150]");
}

TEST(BobDatabaseReader, DeeplyNestedMetadataIsInputErrorNotAStackOverflow) {
  const TempDir dir;
  write_example_route(dir);
  // 50,000 nested brackets (100 kB) overflowed the stack inside OpenCV's YAML parser.
  write_text(dir / kBobMetadataFile,
             "metadata:\n  description: " + std::string(50000, '[') + std::string(50000, ']'));
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobMetadataFile).string(), "bytes");
  // Small but deep, in flow style and in block style ("- - - ..." opens a sequence each).
  write_text(dir / kBobMetadataFile, "metadata:\n  description: " + std::string(2000, '{'));
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobMetadataFile).string(), "nested");
  std::string dashes = "metadata:\n  description:\n";
  for (int i = 0; i < 5000; ++i) dashes += "- ";
  write_text(dir / kBobMetadataFile, dashes + "x\n");
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobMetadataFile).string(), "nested");
  // Brackets in quotes and comments are text, not nesting.
  write_text(dir / kBobMetadataFile, std::string(kExampleRouteMetadata) + "   description: \"" +
                                         std::string(100, '[') + "\" # " + std::string(100, '{') +
                                         "\n");
  EXPECT_EQ(BobDatabaseReader(dir.path()).info().description, std::string(100, '['));
}

// Found by tests/fuzz/bob_metadata_fuzz.cpp: OpenCV's parser threw std::length_error on the
// key ":r" (a valid YAML name, which BoB does not use).
TEST(BobDatabaseReader, MetadataWithAKeyOpenCvFailedOnIsRead) {
  const TempDir dir;
  write_example_route(dir);
  write_text(dir / kBobMetadataFile, "%YAML:1.0\n---\nmetadata:\n   type: grid\n   :r\n");
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, "missing column 'Grid X'");  // type was read
}

// Found by tests/fuzz/bob_metadata_fuzz.cpp: OpenCV's YAML parser looped forever on these.
TEST(BobDatabaseReader, MetadataThatHungOpenCvIsInputError) {
  const TempDir dir;
  write_example_route(dir);
  for (const std::string text : {" - a\nt\"\nb", "  - a\nt\"\n  - "}) {
    write_text(dir / kBobMetadataFile, text);
    EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobMetadataFile).string());
  }
}

TEST(BobDatabaseReader, NonFiniteMetadataNumberIsInputError) {
  const TempDir dir;
  write_example_route(dir);
  write_text(dir / kBobMetadataFile, "metadata:\n  type: route\n  frameRate: .nan\n");
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobMetadataFile).string(),
                     "metadata.frameRate is not a finite number");
}

TEST(BobDatabaseReader, AbsurdPositionIsInputErrorNamingLineAndColumn) {
  const TempDir dir;
  write_example_route(dir);
  write_text(dir / kBobEntriesFile,
             "X [mm], Y [mm], Z [mm], Heading [degrees], Filename\n"
             "6300, 8450, 10, 219.962, image_00000.png\n"
             "6300, 1e160, 10, 219.962, image_00001.png\n");
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobEntriesFile).string() + ":3",
                     "'Y [mm]'", "not a position");
}

TEST(BobDatabaseReader, UnknownDatabaseTypeIsInputErrorNamingMetadata) {
  const TempDir dir;
  write_example_route(dir);
  write_text(dir / kBobMetadataFile, "%YAML:1.0\n---\nmetadata:\n   type: spiral\n");
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobMetadataFile).string(), "spiral");
}

TEST(BobDatabaseReader, UnparsableMetadataIsInputErrorNamingIt) {
  const TempDir dir;
  write_example_route(dir);
  write_text(dir / kBobMetadataFile, "metadata: [ : \n  x");
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobMetadataFile).string());
}

TEST(BobDatabaseReader, EntriesWithoutRowsIsInputError) {
  const TempDir dir;
  write_text(dir / kBobEntriesFile, "X [mm], Y [mm], Z [mm], Heading [degrees], Filename\n");
  EXPECT_INPUT_ERROR(BobDatabaseReader{dir.path()}, (dir / kBobEntriesFile).string(), "no entries");
}

}  // namespace
}  // namespace omninav::io
