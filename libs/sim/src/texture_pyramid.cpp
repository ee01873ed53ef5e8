#include "texture_pyramid.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace omninav::sim {

TexturePyramid::TexturePyramid(const cv::Mat& texture_bgr8) {
  cv::Mat level;
  texture_bgr8.convertTo(level, CV_32FC3, 1.0 / 255.0);
  levels_.push_back(level);
  while (levels_.back().cols > 1 && levels_.back().rows > 1) {
    cv::Mat smaller;
    cv::pyrDown(levels_.back(), smaller);
    levels_.push_back(smaller);
  }
}

cv::Vec3f TexturePyramid::bilinear(const cv::Mat& image, const cv::Vec2f& uv) const {
  const float x = (uv[0] - std::floor(uv[0])) * image.cols - 0.5f;
  const float y = (1.f - (uv[1] - std::floor(uv[1]))) * image.rows - 0.5f;
  const float x_floor = std::floor(x), y_floor = std::floor(y);
  const float fx = x - x_floor, fy = y - y_floor;
  // x and y lie in [-0.5, size - 0.5), so their floors lie in [-1, size - 1]: wrapping needs a
  // comparison, not a (slow) integer division.
  int x0 = static_cast<int>(x_floor), y0 = static_cast<int>(y_floor);
  if (x0 < 0) x0 += image.cols;
  if (y0 < 0) y0 += image.rows;
  const int x1 = x0 + 1 == image.cols ? 0 : x0 + 1;
  const int y1 = y0 + 1 == image.rows ? 0 : y0 + 1;
  const auto* row0 = image.ptr<cv::Vec3f>(y0);
  const auto* row1 = image.ptr<cv::Vec3f>(y1);
  return (row0[x0] * (1.f - fx) + row0[x1] * fx) * (1.f - fy) +
         (row1[x0] * (1.f - fx) + row1[x1] * fx) * fy;
}

cv::Vec3f TexturePyramid::sample(const cv::Vec2f& uv, float level) const {
  const float clamped = std::clamp(level, 0.f, static_cast<float>(levels_.size() - 1));
  const int lower = static_cast<int>(clamped);
  const float blend = clamped - lower;
  const cv::Vec3f fine = bilinear(levels_[lower], uv);
  if (blend <= 0.f || lower + 1 >= static_cast<int>(levels_.size())) return fine;
  return fine * (1.f - blend) + bilinear(levels_[lower + 1], uv) * blend;
}

}  // namespace omninav::sim
