#pragma once
// Changing the number of columns of a panorama, for running the compass at another angular
// resolution than the camera's (Labrosse 2006, §3.4.1: 1 to 3 pixels per degree).
//
// Columns are resampled circularly (column W−1 is next to column 0) and keep docs/design.md's
// azimuths: column c of the result looks where column c·W_in/W_out of the input looks (column
// centres at integer positions, so the front stays at 0.25·W). Each output column is a
// weighted mean of input columns under a triangle ("tent") of half-width max(1, W_in/W_out)
// input columns centred there: linear interpolation when enlarging, an anti-aliasing average
// when reducing (1080 → 360: weights 1/9·(1, 2, 3, 2, 1) over five columns). Rows are kept as
// they are. Values are rounded to the nearest integer.

#include <opencv2/core.hpp>

namespace omninav::compass {

// Throws InputError for an empty or non-8-bit image, UsageError for width_px < 1.
cv::Mat resample_columns(const cv::Mat& panorama, int width_px);

}  // namespace omninav::compass
