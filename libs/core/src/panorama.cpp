#include "omninav/core/panorama.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"

namespace omninav {

double azimuth_of_column(double column, int width_px) {
  return wrap_angle(kPi / 2.0 - kTwoPi * column / width_px);
}

double column_of_azimuth(double azimuth_rad, int width_px) {
  const double column = (kPi / 2.0 - azimuth_rad) * width_px / kTwoPi;
  double wrapped = std::fmod(column, static_cast<double>(width_px));
  if (wrapped < 0.0) wrapped += width_px;
  return wrapped >= width_px ? 0.0 : wrapped;
}

double shift_px_of_rotation(double turn_rad, int width_px) {
  return turn_rad * width_px / kTwoPi;
}

double rotation_of_shift_px(double shift_px, int width_px) {
  return shift_px * kTwoPi / width_px;
}

cv::Mat roll_columns(const cv::Mat& panorama, int shift_px) {
  const int width = panorama.cols;
  if (width == 0) return panorama.clone();
  const int shift = ((shift_px % width) + width) % width;
  cv::Mat rolled(panorama.size(), panorama.type());
  if (shift == 0) {
    panorama.copyTo(rolled);
    return rolled;
  }
  // Content at [0, W-shift) moves to [shift, W); the last `shift` columns wrap to the front.
  panorama.colRange(0, width - shift).copyTo(rolled.colRange(shift, width));
  panorama.colRange(width - shift, width).copyTo(rolled.colRange(0, shift));
  return rolled;
}

cv::Mat roll_columns_fractional(const cv::Mat& panorama, double shift_px) {
  const double whole = std::floor(shift_px);
  const double fraction = shift_px - whole;
  const cv::Mat lower = roll_columns(panorama, static_cast<int>(whole));
  if (fraction == 0.0) return lower;
  const cv::Mat upper = roll_columns(panorama, static_cast<int>(whole) + 1);
  cv::Mat blended;
  cv::addWeighted(lower, 1.0 - fraction, upper, fraction, 0.0, blended);
  return blended;
}

ChannelOrder channel_order_of(const std::string& name, const std::string& what) {
  if (name == "bgr") return ChannelOrder::kBgr;
  if (name == "rgb") return ChannelOrder::kRgb;
  throw UsageError(what + " '" + name + "': expected bgr or rgb");
}

const char* to_string(ChannelOrder order) {
  return order == ChannelOrder::kRgb ? "rgb" : "bgr";
}

cv::Mat to_bgr(const cv::Mat& image, ChannelOrder order) {
  if (order == ChannelOrder::kBgr || image.channels() != 3) return image;
  cv::Mat bgr;
  cv::cvtColor(image, bgr, cv::COLOR_RGB2BGR);
  return bgr;
}

void require_panorama(const cv::Mat& panorama, const std::string& what) {
  if (panorama.empty()) throw InputError(what + ": empty image");
  if (panorama.depth() != CV_8U || (panorama.channels() != 1 && panorama.channels() != 3)) {
    throw InputError(what + ": expected an 8-bit grey or colour image, got type " +
                     std::to_string(panorama.type()));
  }
}

double PanoramaGeometry::elevation_of_row(double row) const {
  return elevation_max_rad - (row + 0.5) * rad_per_row();
}

double PanoramaGeometry::row_of_elevation(double elevation_rad) const {
  return (elevation_max_rad - elevation_rad) / rad_per_row() - 0.5;
}

void load_panorama_geometry(const ConfigReader& section, PanoramaGeometry& geometry) {
  section.read("width_px", geometry.width_px, 8, 16384);
  section.read("height_px", geometry.height_px, 1, 4096);
  section.read_deg("elevation_min_deg", geometry.elevation_min_rad, -90.0, 89.0);
  section.read_deg("elevation_max_deg", geometry.elevation_max_rad, -89.0, 90.0);
  if (geometry.elevation_max_rad <= geometry.elevation_min_rad) {
    throw ConfigError(section.source_name() +
                      ": key 'panorama.elevation_max_deg' must be above elevation_min_deg");
  }
}

}  // namespace omninav
