#pragma once
// A panorama's lines (signature.hpp: one per row in luminance mode, three per row, blue rows
// first, per channel) as the floats the transforms take, one line at a time into a small
// buffer: no grey image is made, and the line stays in the L1 cache for its transform.

#include <opencv2/core.hpp>

#include "omninav/signature/signature.hpp"

namespace omninav::signature::detail {

// Writes line `line` of `panorama` (8-bit, 1 or 3 channels, checked by the caller) into `dst`
// (panorama.cols floats). A grey panorama gives its row in either mode (three equal channels
// per channel). Luminance of a BGR panorama is OpenCV's: cv::cvtColor(COLOR_BGR2GRAY) rounds
// to whole grey levels, Y = (3735·B + 19235·G + 9798·R + 2^14) >> 15 (ITU-R BT.601 (0.114,
// 0.587, 0.299) in OpenCV's 15-bit fixed point, its RGB2Gray<uchar>), and this gives the very
// same integers (tested on all 2^24 colours), so signatures and the maps made with them do not
// change.
void load_line(const cv::Mat& panorama, ColourMode mode, int line, float* dst);

}  // namespace omninav::signature::detail
