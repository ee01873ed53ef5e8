#pragma once
// The panorama: an unwrapped omnidirectional image, a W×H cv::Mat of 8-bit pixels (1 channel,
// or 3 in OpenCV's BGR order), with the column convention of docs/design.md:
//   - the robot's front is at column 0.25·W and its back at 0.75·W;
//   - column 0 is the robot's left, and the azimuth relative to the robot (counter-clockwise
//     positive, 0 straight ahead) decreases as the column index grows:
//         azimuth(c) = π/2 − 2π·c/W   (column c's centre)
//   - so a counter-clockwise turn of the robot by δ moves the content by +δ·W/(2π) columns.
// Rows run from the top (highest elevation) down; PanoramaGeometry says which elevations.

#include <opencv2/core.hpp>
#include <string>

#include "omninav/core/angles.hpp"

namespace omninav {

// Azimuth relative to the robot of column `column` (fractional columns allowed), in (-π, π].
double azimuth_of_column(double column, int width_px);

// The column, in [0, W), that looks along `azimuth_rad` relative to the robot.
double column_of_azimuth(double azimuth_rad, int width_px);

// How many columns the content moves when the robot turns counter-clockwise by `turn_rad`.
double shift_px_of_rotation(double turn_rad, int width_px);

// The robot's counter-clockwise turn that moves the content by `shift_px` columns.
double rotation_of_shift_px(double shift_px, int width_px);

// Rolls the columns circularly so that content at column c moves to c + shift_px (mod W):
// the image the robot sees after turning counter-clockwise by shift_px·2π/W on the spot.
cv::Mat roll_columns(const cv::Mat& panorama, int shift_px);

// As roll_columns, for a fractional shift, by linear interpolation between the two nearest
// whole-column rolls (a mild low-pass; exact when shift_px is whole).
cv::Mat roll_columns_fractional(const cv::Mat& panorama, double shift_px);

// The order of a colour image's channels. omninav works in OpenCV's BGR, which its readers give;
// an image from elsewhere in RGB (PIL, imageio, a ROS rgb8 message) must say so, or its red
// and blue rows trade places and its signature and dissimilarities change.
enum class ChannelOrder { kBgr, kRgb };

// "bgr" or "rgb"; UsageError naming `what` otherwise.
ChannelOrder channel_order_of(const std::string& name, const std::string& what = "channel order");
const char* to_string(ChannelOrder order);

// `image` in BGR: a 3-channel RGB image with its channels swapped (a new image), any other
// image as it is (a grey image has no order).
cv::Mat to_bgr(const cv::Mat& image, ChannelOrder order);

// Throws InputError naming `what` unless `panorama` is a non-empty 8-bit 1- or 3-channel image.
void require_panorama(const cv::Mat& panorama, const std::string& what);

// The vertical layout of a panorama: its size and the elevations its rows cover, linear in
// elevation (equiangular), row 0 at the top. Used by the renderer; real unwrapped panoramas
// only approximate it (the mirror's profile is not modelled, Labrosse 2006, §3.1).
struct PanoramaGeometry {
  int width_px = 360;                            // one column per degree (Labrosse 2006, §3.1)
  int height_px = 45;                            // rows
  double elevation_min_rad = deg_to_rad(-30.0);  // bottom edge of the last row
  double elevation_max_rad = deg_to_rad(15.0);   // top edge of the first row

  double elevation_of_row(double row) const;  // row centre r ↦ elevation
  double row_of_elevation(double elevation_rad) const;
  double rad_per_row() const { return (elevation_max_rad - elevation_min_rad) / height_px; }
};

class ConfigReader;

// Reads the `panorama:` section of camera.yaml (keys width_px, height_px, elevation_min_deg,
// elevation_max_deg) into `geometry`.
void load_panorama_geometry(const ConfigReader& section, PanoramaGeometry& geometry);

}  // namespace omninav
