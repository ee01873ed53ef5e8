#pragma once
// What the bag tests share: the rendered route database (tests/io/bags/route, written by
// `omninav render`) whose frames every bag holds, the writers of bags that do not use omninav's
// code (tests/io/bags: Debian's python3-rosbag, Python's sqlite3, and MCAP files committed from
// @mcap/core), and the frame-for-frame comparison with the database.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "io_test_support.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/io/bag_sequence.hpp"
#include "omninav/io/bob_database.hpp"

namespace omninav::io::testing {

inline const std::filesystem::path kBagData = OMNINAV_BAG_TEST_DIR;
inline constexpr double kStampBaseS = 1'700'000'000.0;  // bob_route.py's STAMP_BASE_S

inline std::vector<Frame> route_frames() {
  BobDatabaseReader reader(kBagData / "route");
  return read_all(reader);
}

// Runs one of tests/io/bags' Python writers with Debian's python3 (where python3-rosbag is):
// `script` route `out` `arguments`. Returns `out`.
inline std::filesystem::path write_with(const std::string& script, const std::filesystem::path& out,
                                        const std::string& arguments) {
  const std::string command = std::string(OMNINAV_DEBIAN_PYTHON) + " " +
                              (kBagData / script).string() + " " + (kBagData / "route").string() +
                              " " + out.string() + " " + arguments;
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return out;
}

enum class Pixels { kColour, kGrey };

// The grey levels the writers put in mono8 and mono16 images (bob_route.py's grey(), the
// BT.601 weights in 14-bit integers).
inline cv::Mat writers_grey(const cv::Mat& bgr) {
  cv::Mat grey(bgr.size(), CV_8UC1);
  for (int row = 0; row < bgr.rows; ++row) {
    for (int col = 0; col < bgr.cols; ++col) {
      const cv::Vec3b pixel = bgr.at<cv::Vec3b>(row, col);
      grey.at<uchar>(row, col) =
          static_cast<uchar>((pixel[2] * 4899 + pixel[1] * 9617 + pixel[0] * 1868 + 8192) >> 14);
    }
  }
  return grey;
}

// Checks `frames` against the database frame for frame: pixels (BGR, or writers_grey of the
// database's), stamps, and (when `poses`) the poses, for the first `count` frames.
inline void expect_route(const std::vector<Frame>& frames, Pixels pixels, bool poses,
                         std::size_t count = 0) {
  const std::vector<Frame> route = route_frames();
  if (count == 0) count = route.size();
  ASSERT_EQ(frames.size(), count);
  for (std::size_t i = 0; i < count; ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    cv::Mat expected = route[i].image;
    if (pixels == Pixels::kGrey) expected = writers_grey(route[i].image);
    EXPECT_TRUE(same_pixels(frames[i].image, expected))
        << frames[i].image.size() << " type " << frames[i].image.type() << " vs " << expected.size()
        << " type " << expected.type() << "; max difference "
        << (frames[i].image.size() == expected.size() && frames[i].image.type() == expected.type()
                ? cv::norm(frames[i].image, expected, cv::NORM_INF)
                : -1.0);
    EXPECT_EQ(frames[i].index, static_cast<int>(i));
    ASSERT_TRUE(frames[i].time_s.has_value());
    EXPECT_NEAR(*frames[i].time_s, kStampBaseS + *route[i].time_s, 1e-6);
    if (!poses) {
      EXPECT_FALSE(frames[i].truth.has_value());
      continue;
    }
    ASSERT_TRUE(frames[i].truth.has_value());
    EXPECT_NEAR(frames[i].truth->x_m, route[i].truth->x_m, 1e-9);
    EXPECT_NEAR(frames[i].truth->y_m, route[i].truth->y_m, 1e-9);
    EXPECT_NEAR(frames[i].truth->z_m, route[i].truth->z_m, 1e-9);
    EXPECT_NEAR(frames[i].truth->heading_rad, route[i].truth->heading_rad, 1e-9);
    EXPECT_NEAR(frames[i].truth->pitch_rad, 0.0, 1e-12);
    EXPECT_NEAR(frames[i].truth->roll_rad, 0.0, 1e-12);
  }
}

// The frames of a damaged bag up to the damage; expects the InputError there, naming the file
// and saying `what`.
inline std::vector<Frame> read_until_error(const std::filesystem::path& bag,
                                           const BagOptions& options, const std::string& what) {
  std::unique_ptr<SequenceReader> reader = open_bag(bag, options);
  std::vector<Frame> frames;
  try {
    while (std::optional<Frame> frame = reader->next()) frames.push_back(std::move(*frame));
    ADD_FAILURE() << bag << " read to its end";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(bag.filename().string()), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  }
  return frames;
}

inline std::vector<Frame> read_bag(const std::filesystem::path& bag, const BagOptions& options) {
  std::unique_ptr<SequenceReader> reader = open_bag(bag, options);
  return read_all(*reader);
}

}  // namespace omninav::io::testing
