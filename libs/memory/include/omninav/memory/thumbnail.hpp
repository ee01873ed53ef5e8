#pragma once
// The small copy of its panorama a place keeps (memory.yaml's thumbnail_width_px): what a figure
// draws, and the snapshot min-warping compares a view with to find the way to the place (home
// vectors, compass/min_warping.hpp).

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace omninav::memory {

// The panorama scaled to `width_px` wide (its aspect ratio kept, area-averaged), PNG-encoded.
std::vector<std::uint8_t> make_thumbnail(const cv::Mat& panorama, int width_px);

// A stored thumbnail, decoded to 3 channels. Throws InputError naming `place_name` when there is
// none (the map was explored with thumbnail_width_px 0) or it cannot be decoded.
cv::Mat decode_thumbnail(const std::vector<std::uint8_t>& png, const std::string& place_name);

}  // namespace omninav::memory
