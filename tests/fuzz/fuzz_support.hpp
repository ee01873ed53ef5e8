#pragma once
// What the libFuzzer targets of tests/fuzz share: a scratch folder of their own, files written
// into it, and the one rule of every target: a parser may reject its input only with one of
// omninav's errors (core/errors.hpp). Any other exception escapes, and libFuzzer reports it
// as a crash, as it does a sanitizer's finding, a hang or a leak.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <string_view>

#include "omninav/core/errors.hpp"

namespace omninav::fuzz {

// A folder of this process's own under the temporary directory, made once and kept (libFuzzer
// ends a process with exit(), and the folder holds only a few small files).
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "omninav-fuzz-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) std::abort();
    return std::filesystem::path(pattern);
  }();
  return dir;
}

inline void write_file(const std::filesystem::path& file, std::string_view content) {
  std::ofstream stream(file, std::ios::binary | std::ios::trunc);
  stream.write(content.data(), static_cast<std::streamsize>(content.size()));
  if (!stream) std::abort();
}

// scratch_dir()/<name>, made on the first call, holding a small image, 0.png (8 x 4 pixels),
// that the rows of a fuzzed file may name.
inline std::filesystem::path folder_with_image(const std::string& name) {
  const std::filesystem::path dir = scratch_dir() / name;
  std::filesystem::create_directories(dir);
  if (!cv::imwrite((dir / "0.png").string(), cv::Mat(4, 8, CV_8UC3, cv::Scalar(1, 2, 3)))) {
    std::abort();
  }
  return dir;
}

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// Runs `parse`, accepting omninav's own errors as the clean rejection of a bad input.
template <typename Parse>
int expect_clean(Parse&& parse) {
  try {
    parse();
  } catch (const omninav::Error&) {
  }
  return 0;
}

}  // namespace omninav::fuzz
