#include "omninav/core/errors.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

namespace omninav {
namespace {

namespace fs = std::filesystem;

TEST(UnreadableFileReason, SaysWhatThePathIsInstead) {
  const fs::path dir = fs::temp_directory_path() / ("omninav_errors_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "plain.txt") << "x";
  ASSERT_EQ(::mkfifo((dir / "pipe").c_str(), 0600), 0);
  EXPECT_EQ(unreadable_file_reason(dir / "absent.avi", "video file"), "no such video file");
  EXPECT_EQ(unreadable_file_reason(dir, "video file"), "is a folder, not a video file");
  EXPECT_EQ(unreadable_file_reason(dir / "pipe", "video file"), "is a FIFO, not a video file");
  EXPECT_EQ(unreadable_file_reason("/dev/null", "image file"), "is a device, not an image file");
  // A path that cannot be reached is not "not found" (an unreadable folder says so too).
  EXPECT_EQ(unreadable_file_reason(dir / "plain.txt" / "camera.yaml", "configuration file"),
            "cannot reach the configuration file (Not a directory)");
  fs::remove_all(dir);
}

TEST(PrintableName, KeepsUtf8AndEscapesControlsAndBytesThatAreNotUtf8) {
  EXPECT_EQ(printable_name("/camera/image_raw"), "/camera/image_raw");
  EXPECT_EQ(printable_name("/caméra"), "/caméra");
  EXPECT_EQ(printable_name(std::string("/cam\x18\xff\n", 7)), "/cam\\x18\\xff\\x0a");
  EXPECT_EQ(printable_name("\xc0\xaf"), "\\xc0\\xaf");           // an overlong '/'
  EXPECT_EQ(printable_name("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a surrogate
  EXPECT_EQ(printable_name("\xe2\x82"), "\\xe2\\x82");           // cut short
}

}  // namespace
}  // namespace omninav
