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

namespace {

// floor() for the values texture lookup meets. std::floor is a library call on the x86-64
// baseline (no SSE4.1 rounding instruction), and it dominated the renderer's profile.
inline int fast_floor(float value) {
  const int truncated = static_cast<int>(value);
  return truncated - (value < static_cast<float>(truncated) ? 1 : 0);
}

}  // namespace

cv::Vec3f TexturePyramid::bilinear(const cv::Mat& image, const cv::Vec2f& uv) const {
  // Repeat wrapping: keep the fractional part of the texture coordinates.
  const float u = uv[0] - static_cast<float>(fast_floor(uv[0]));
  const float v = uv[1] - static_cast<float>(fast_floor(uv[1]));
  const float x = u * image.cols - 0.5f;
  const float y = (1.f - v) * image.rows - 0.5f;
  // x and y lie in [-0.5, size - 0.5], so their floors lie in [-1, size - 1]: wrapping needs a
  // comparison, not a (slow) integer division.
  int x0 = fast_floor(x), y0 = fast_floor(y);
  const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
  if (x0 < 0) x0 += image.cols;
  if (y0 < 0) y0 += image.rows;
  if (x0 >= image.cols) x0 -= image.cols;
  if (y0 >= image.rows) y0 -= image.rows;
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
