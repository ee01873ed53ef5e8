#pragma once
// What the io tests share: a temporary folder that removes itself, and small images whose
// pixels encode the frame index, so that a test can tell which frame it got and in what order.

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

namespace omninav::io::testing {

class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string name = std::string("omninav_io_") + (test ? test->name() : "test") + "_" +
                             std::to_string(::getpid()) + "_" + std::to_string(counter++);
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// A 36x8 BGR image (by default) unique to `index`: channel 0 holds the index in every pixel,
// channels 1 and 2 a column and row ramp, so that a transposed or shifted image differs too.
inline cv::Mat make_image(int index, cv::Size size = {36, 8}) {
  cv::Mat image(size, CV_8UC3);
  for (int row = 0; row < size.height; ++row) {
    for (int col = 0; col < size.width; ++col) {
      image.at<cv::Vec3b>(row, col) = cv::Vec3b(
          static_cast<uchar>(index), static_cast<uchar>(7 * col), static_cast<uchar>(31 * row));
    }
  }
  return image;
}

// The index make_image() encoded, read back from the first pixel.
inline int index_of(const cv::Mat& image) {
  return image.at<cv::Vec3b>(0, 0)[0];
}

inline bool same_pixels(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

inline void write_image(const std::filesystem::path& file, const cv::Mat& image) {
  ASSERT_TRUE(cv::imwrite(file.string(), image)) << file;
}

inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream stream(file, std::ios::binary);
  stream << text;
  ASSERT_TRUE(stream.good()) << file;
}

}  // namespace omninav::io::testing

// Expects `statement` to throw omninav::InputError whose message contains every one of the
// given fragments (file names, line numbers, sizes).
#define EXPECT_INPUT_ERROR(statement, ...)                                                  \
  do {                                                                                      \
    try {                                                                                   \
      statement;                                                                            \
      ADD_FAILURE() << "expected InputError from " #statement;                              \
    } catch (const ::omninav::InputError& error) {                                          \
      const std::string message = error.what();                                             \
      for (const std::string& fragment : std::initializer_list<std::string>{__VA_ARGS__}) { \
        EXPECT_NE(message.find(fragment), std::string::npos)                                \
            << "message: " << message << "\nmissing: " << fragment;                         \
      }                                                                                     \
    }                                                                                       \
  } while (false)
