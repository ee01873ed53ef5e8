// DatabaseWriter: round trips through BobDatabaseReader, BoB's file layout, and the promise
// that nothing is half-written.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "io_test_support.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/io/bob_database.hpp"

namespace omninav::io {
namespace {

using testing::index_of;
using testing::make_image;
using testing::same_pixels;
using testing::TempDir;

// Numbers are stored exactly (shortest round-trip text); what remains is the m→mm→m and
// rad→deg→rad arithmetic, a few ulps.
constexpr double kRoundTrip = 1e-9;

std::string read_text(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

std::string first_line(const std::filesystem::path& file) {
  std::ifstream stream(file);
  std::string line;
  std::getline(stream, line);
  return line;
}

// A route frame with awkward numbers: no short decimal represents them.
Frame route_frame(int index) {
  Frame frame;
  frame.index = index;
  frame.image = make_image(index);
  frame.source = "generated#" + std::to_string(index);
  frame.time_s = 0.1 * index + 1.0 / 3.0;
  frame.truth = CameraPose{1.0 / 3.0 + index, -2.718281828459045 * index,
                           0.123456789,       deg_to_rad(170.0) - 0.7 * index,
                           0.01 * index,      -0.02 * index};
  return frame;
}

DatabaseInfo route_info() {
  DatabaseInfo info;
  info.camera_name = "renderer";
  info.description = "rendered room: seed 7, \"quoted\", colon: yes";
  info.frame_rate_hz = 10.0;
  info.needs_unwrapping = false;
  return info;
}

void expect_same_pose(const CameraPose& actual, const CameraPose& expected) {
  EXPECT_NEAR(actual.x_m, expected.x_m, kRoundTrip);
  EXPECT_NEAR(actual.y_m, expected.y_m, kRoundTrip);
  EXPECT_NEAR(actual.z_m, expected.z_m, kRoundTrip);
  EXPECT_NEAR(actual.heading_rad, expected.heading_rad, kRoundTrip);
  EXPECT_NEAR(actual.pitch_rad, expected.pitch_rad, kRoundTrip);
  EXPECT_NEAR(actual.roll_rad, expected.roll_rad, kRoundTrip);
}

TEST(DatabaseWriter, RouteRoundTripKeepsPosesImagesTimesAndInfo) {
  const TempDir dir;
  const std::filesystem::path folder = dir / "route";
  {
    DatabaseWriter writer(folder, route_info());
    for (int i = 0; i < 5; ++i) writer.add(route_frame(i));
    EXPECT_EQ(writer.size(), 5u);
    writer.finish();
  }

  BobDatabaseReader reader(folder);
  EXPECT_FALSE(reader.info().is_grid);
  EXPECT_EQ(reader.info().camera_name, "renderer");
  EXPECT_EQ(reader.info().description, route_info().description);
  EXPECT_EQ(reader.info().image_size, cv::Size(36, 8));
  EXPECT_EQ(reader.info().frame_rate_hz, std::optional<double>(10.0));
  EXPECT_EQ(reader.info().needs_unwrapping, std::optional<bool>(false));
  const std::vector<Frame> frames = read_all(reader);
  ASSERT_EQ(frames.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    const Frame expected = route_frame(i);
    EXPECT_TRUE(same_pixels(frames[i].image, expected.image)) << "frame " << i;  // PNG: lossless
    ASSERT_TRUE(frames[i].truth);
    expect_same_pose(*frames[i].truth, *expected.truth);
    ASSERT_TRUE(frames[i].time_s);
    EXPECT_NEAR(*frames[i].time_s, *expected.time_s, kRoundTrip);
    EXPECT_FALSE(reader.entries()[i].grid);
  }
  EXPECT_EQ(std::filesystem::path(frames[3].source).filename(), "image_00003.png");
}

TEST(DatabaseWriter, OdometryBesideTheTruthRoundTrips) {
  const TempDir dir;
  const std::filesystem::path folder = dir / "odometry";
  const auto odometry_of = [](int i) {
    return CameraPose{0.5 + 0.31 * i, -0.2 * i, 0.123456789, deg_to_rad(10.0 * i), 0.0, 0.0};
  };
  {
    DatabaseWriter writer(folder, route_info());
    for (int i = 0; i < 3; ++i) {
      Frame frame = route_frame(i);
      frame.odometry = odometry_of(i);
      writer.add(frame);
    }
    // Odometry for some frames and not others cannot be written.
    EXPECT_THROW(writer.add(route_frame(3)), UsageError);
    writer.finish();
  }
  EXPECT_NE(first_line(folder / kBobEntriesFile)
                .find("Odometry X [mm], Odometry Y [mm], Odometry Heading [degrees]"),
            std::string::npos);
  BobDatabaseReader reader(folder);
  const std::vector<Frame> frames = read_all(reader);
  ASSERT_EQ(frames.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(frames[i].odometry) << "frame " << i;
    expect_same_pose(*frames[i].odometry, odometry_of(i));
    expect_same_pose(*frames[i].truth, *route_frame(i).truth);  // the truth stays the truth
  }
  // A database without the columns has no odometry.
  const std::filesystem::path plain = dir / "plain";
  {
    DatabaseWriter writer(plain, route_info());
    writer.add(route_frame(0));
    writer.finish();
  }
  BobDatabaseReader plain_reader(plain);
  EXPECT_FALSE(read_all(plain_reader).front().odometry);
}

TEST(DatabaseWriter, GridRoundTripKeepsIndicesAndUsesBobGridNames) {
  const TempDir dir;
  DatabaseInfo info;
  info.is_grid = true;
  info.grid = GridGeometry{{-500.0, 0.0, 10.0}, {500.0, 1000.0, 0.0}, {3, 2, 1}};
  {
    DatabaseWriter writer(dir.path(), info);
    int index = 0;
    for (int y = 0; y < 2; ++y) {
      for (int x = 0; x < 3; ++x) {
        Frame frame;
        frame.image = make_image(index++);
        frame.truth = CameraPose{0.5 * x - 0.5, 1.0 * y, 0.01, 0.0, 0.0, 0.0};
        writer.add(frame, std::array{x, y, 0});
      }
    }
    writer.finish();
  }
  // BoB's GridRecorder naming: the position in whole mm, signed, 7 characters each.
  EXPECT_TRUE(std::filesystem::exists(dir / "image_-000500_+000000_+000010.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "image_+000500_+001000_+000010.png"));

  BobDatabaseReader reader(dir.path());
  EXPECT_TRUE(reader.info().is_grid);
  // The geometry as BoB's GridRecorder writes it, read back.
  ASSERT_TRUE(reader.info().grid);
  EXPECT_EQ(reader.info().grid->begin_mm, info.grid->begin_mm);
  EXPECT_EQ(reader.info().grid->separation_mm, info.grid->separation_mm);
  EXPECT_EQ(reader.info().grid->size, info.grid->size);
  EXPECT_EQ(reader.grid_spacing_m(), std::optional<double>(0.5));
  ASSERT_EQ(reader.entries().size(), 6u);
  EXPECT_EQ(reader.entries()[4].grid, (std::array{1, 1, 0}));
  ASSERT_TRUE(reader.entries()[4].truth);
  EXPECT_NEAR(reader.entries()[4].truth->x_m, 0.0, kRoundTrip);
  EXPECT_NEAR(reader.entries()[4].truth->y_m, 1.0, kRoundTrip);
  EXPECT_FALSE(reader.entries()[4].time_s);  // no times given, no frame rate
  const std::vector<Frame> frames = read_all(reader);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(index_of(frames[i].image), i);
}

TEST(DatabaseWriter, WritesBobLayout) {
  const TempDir dir;
  {
    DatabaseWriter writer(dir.path(), route_info());
    writer.add(route_frame(0));
    writer.finish();
  }
  // The header BoB's ImageDatabase::addNewEntries writes, then our capture times.
  EXPECT_EQ(first_line(dir / kBobEntriesFile),
            "X [mm], Y [mm], Z [mm], Heading [degrees], Pitch [degrees], Roll [degrees], "
            "Filename, Timestamp [ms]");
  // BoB's Recorder writes the metadata through cv::FileStorage: this layout.
  const std::string yaml = read_text(dir / kBobMetadataFile);
  EXPECT_EQ(yaml.rfind("%YAML:1.0\n---\nmetadata:\n", 0), 0u) << yaml;
  EXPECT_NE(yaml.find("   type: route\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("   camera:\n      name: renderer\n      resolution: [ 36, 8 ]\n"),
            std::string::npos)
      << yaml;
  EXPECT_NE(yaml.find("   frameRate: 10.\n"), std::string::npos) << yaml;
  EXPECT_FALSE(std::filesystem::exists(dir / ".omninav_staging"));
}

TEST(DatabaseWriter, WrittenDatabaseOpensAsSequence) {
  const TempDir dir;
  {
    DatabaseWriter writer(dir.path(), route_info());
    writer.add(route_frame(0));
    writer.finish();
  }
  const std::unique_ptr<SequenceReader> sequence = open_sequence(dir.path());
  EXPECT_NE(sequence->describe().find("BoB database"), std::string::npos);
}

TEST(DatabaseWriter, RefusesAnExistingDatabaseUnlessToldToOverwrite) {
  const TempDir dir;
  {
    DatabaseWriter writer(dir.path(), route_info());
    for (int i = 0; i < 3; ++i) writer.add(route_frame(i));
    writer.finish();
  }
  EXPECT_THROW(DatabaseWriter(dir.path(), route_info()), UsageError);

  DatabaseWriter writer(dir.path(), route_info(), /*overwrite=*/true);
  Frame replacement = route_frame(7);
  writer.add(replacement);
  // Until finish(), the old database is intact: its entries and its images.
  {
    BobDatabaseReader old(dir.path());
    const std::vector<Frame> frames = read_all(old);
    ASSERT_EQ(frames.size(), 3u);
    EXPECT_EQ(index_of(frames[0].image), 0);
  }
  writer.finish();
  BobDatabaseReader replaced(dir.path());
  const std::vector<Frame> frames = read_all(replaced);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(index_of(frames[0].image), 7);
}

TEST(DatabaseWriter, DestroyedWithoutFinishLeavesNothing) {
  const TempDir dir;
  const std::filesystem::path folder = dir / "db";
  {
    DatabaseWriter writer(folder, route_info());
    writer.add(route_frame(0));
    writer.add(route_frame(1));
  }
  EXPECT_FALSE(std::filesystem::exists(folder / kBobEntriesFile));
  EXPECT_FALSE(std::filesystem::exists(folder / kBobMetadataFile));
  EXPECT_TRUE(std::filesystem::is_empty(folder)) << "images or staging left behind";
}

TEST(DatabaseWriter, DestroyedWithoutFinishKeepsTheOldDatabase) {
  const TempDir dir;
  {
    DatabaseWriter writer(dir.path(), route_info());
    writer.add(route_frame(0));
    writer.finish();
  }
  {
    DatabaseWriter writer(dir.path(), route_info(), /*overwrite=*/true);
    writer.add(route_frame(5));
  }
  BobDatabaseReader reader(dir.path());
  const std::vector<Frame> frames = read_all(reader);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(index_of(frames[0].image), 0);
}

TEST(DatabaseWriter, RejectsFramesItCannotStore) {
  const TempDir dir;
  DatabaseWriter writer(dir.path(), route_info());
  Frame no_truth = route_frame(0);
  no_truth.truth.reset();
  EXPECT_THROW(writer.add(no_truth), UsageError);
  EXPECT_THROW(writer.add(route_frame(0), std::array{0, 0, 0}), UsageError);  // grid on a route

  writer.add(route_frame(0));
  Frame no_time = route_frame(1);
  no_time.time_s.reset();
  EXPECT_THROW(writer.add(no_time), UsageError);

  Frame other_size = route_frame(2);
  other_size.image = make_image(2, {40, 8});
  other_size.source = "wide.png";
  EXPECT_INPUT_ERROR(writer.add(other_size), "wide.png", "40x8", "36x8");
}

TEST(DatabaseWriter, GridNeedsIndicesAndDistinctPositions) {
  const TempDir dir;
  DatabaseInfo info;
  info.is_grid = true;
  DatabaseWriter writer(dir.path(), info);
  Frame frame = route_frame(0);
  EXPECT_THROW(writer.add(frame), UsageError);  // no grid index
  EXPECT_THROW(writer.add(frame, std::array{0, -1, 0}), UsageError);
  writer.add(frame, std::array{0, 0, 0});
  EXPECT_THROW(writer.add(frame, std::array{1, 0, 0}), UsageError);  // same position, same name
}

TEST(DatabaseWriter, FinishNeedsFramesAndHappensOnce) {
  const TempDir dir;
  DatabaseWriter empty(dir / "empty", route_info());
  EXPECT_THROW(empty.finish(), UsageError);

  DatabaseWriter writer(dir / "once", route_info());
  writer.add(route_frame(0));
  writer.finish();
  EXPECT_THROW(writer.finish(), UsageError);
  EXPECT_THROW(writer.add(route_frame(1)), UsageError);
}

}  // namespace
}  // namespace omninav::io
