#pragma once
// Writing evaluation pictures (plots, contact sheets) as PNG: the one place that does it.

#include <filesystem>
#include <opencv2/core.hpp>

namespace omninav::measures {

// Writes `image` (8- or 16-bit, 1, 3 (BGR) or 4 (BGRA) channels) to `path` as PNG, whatever
// the extension of `path`, whole or not at all (core/output_file.hpp). Parent folders are not
// created. Throws InputError naming the file if it cannot be written, and UsageError if the image
// is empty or of a type PNG cannot hold.
void save_png(const cv::Mat& image, const std::filesystem::path& path);

}  // namespace omninav::measures
