#include "omninav/io/sequence.hpp"

#include <gtest/gtest.h>

#include <opencv2/videoio.hpp>

#include "io_test_support.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/io/bob_database.hpp"
#include "omninav/io/csv_sequence.hpp"
#include "omninav/io/folder_sequence.hpp"
#include "omninav/io/video_sequence.hpp"

namespace omninav::io {
namespace {

using testing::index_of;
using testing::make_image;
using testing::TempDir;
using testing::write_image;
using testing::write_text;

TEST(OpenSequence, FolderOfImages) {
  const TempDir dir;
  write_image(dir / "b2.png", make_image(2));
  write_image(dir / "b10.png", make_image(10));
  const std::unique_ptr<SequenceReader> sequence = open_sequence(dir.path());
  EXPECT_NE(dynamic_cast<FolderSequence*>(sequence.get()), nullptr);
  EXPECT_FALSE(sequence->is_video());
  EXPECT_FALSE(sequence->is_grid());
  EXPECT_FALSE(sequence->needs_unwrapping());
  const std::vector<Frame> frames = read_all(*sequence);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(index_of(frames[0].image), 2);
  EXPECT_EQ(index_of(frames[1].image), 10);
}

TEST(OpenSequence, FolderWithEntriesIsABobDatabase) {
  const TempDir dir;
  write_image(dir / "a.png", make_image(0));
  write_text(dir / kBobEntriesFile,
             "X [mm], Y [mm], Z [mm], Heading [degrees], Filename\n"
             "0, 0, 0, 0, a.png\n");
  EXPECT_NE(dynamic_cast<BobDatabaseReader*>(open_sequence(dir.path()).get()), nullptr);
  EXPECT_FALSE(open_sequence(dir.path())->is_grid()) << "no metadata: a route";
  // The database says what its frames are, through the reader's interface.
  write_text(dir / kBobEntriesFile,
             "X [mm], Y [mm], Z [mm], Heading [degrees], Filename, Grid X, Grid Y, Grid Z\n"
             "0, 0, 0, 0, a.png, 0, 0, 0\n");
  write_text(dir / kBobMetadataFile,
             "%YAML:1.0\n---\nmetadata:\n   type: grid\n   needsUnwrapping: 1\n");
  const std::unique_ptr<SequenceReader> grid = open_sequence(dir.path());
  EXPECT_TRUE(grid->is_grid());
  EXPECT_TRUE(grid->needs_unwrapping());
  EXPECT_FALSE(grid->is_video());
}

TEST(OpenSequence, FolderWithMetadataButNoEntriesIsInputErrorNotAPlainFolder) {
  const TempDir dir;
  write_image(dir / "a.png", make_image(0));
  write_text(dir / kBobMetadataFile, "metadata:\n  type: route\n");
  EXPECT_INPUT_ERROR(open_sequence(dir.path()), dir.path().string(), kBobMetadataFile,
                     std::string("no ") + kBobEntriesFile);
}

TEST(OpenSequence, CsvFileInAnyCase) {
  const TempDir dir;
  write_image(dir / "a.png", make_image(0));
  write_text(dir / "poses.CSV", "file,x_m,y_m,heading_deg\na.png,0,0,0\n");
  EXPECT_NE(dynamic_cast<CsvSequence*>(open_sequence(dir / "poses.CSV").get()), nullptr);
}

TEST(OpenSequence, OtherFileIsAVideo) {
  const TempDir dir;
  const std::filesystem::path file = dir / "clip.avi";
  {
    cv::VideoWriter writer(file.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 5.0,
                           cv::Size(32, 16));
    if (!writer.isOpened()) GTEST_SKIP() << "cv::VideoWriter cannot write MJPG in AVI here";
    writer.write(cv::Mat(16, 32, CV_8UC3, cv::Scalar::all(100)));
  }
  EXPECT_NE(dynamic_cast<VideoSequence*>(open_sequence(file).get()), nullptr);
  EXPECT_TRUE(open_sequence(file)->is_video());
}

TEST(OpenSequence, NonexistentPathIsInputErrorNamingIt) {
  const TempDir dir;
  const std::filesystem::path missing = dir / "nowhere" / "route";
  EXPECT_INPUT_ERROR(open_sequence(missing), missing.string() + ": no such file or folder");
}

TEST(OpenSequence, FileThatIsNoVideoIsInputErrorNamingIt) {
  const TempDir dir;
  write_text(dir / "notes.txt", "plain text");
  EXPECT_INPUT_ERROR(open_sequence(dir / "notes.txt"), (dir / "notes.txt").string());
}

}  // namespace
}  // namespace omninav::io
