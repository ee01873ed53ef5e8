#pragma once
// A texture as a Gaussian pyramid of float images, sampled trilinearly with repeat wrapping:
// the mip-mapping every renderer uses to avoid aliasing when a pixel covers many texels.

#include <opencv2/core.hpp>
#include <vector>

namespace omninav::sim {

class TexturePyramid {
 public:
  explicit TexturePyramid(const cv::Mat& texture_bgr8);

  // The colour (BGR, 0..1) at texture coordinates `uv` (OBJ convention: v up, repeat) and
  // pyramid level `level` (0 = full resolution; fractional levels blend two).
  cv::Vec3f sample(const cv::Vec2f& uv, float level) const;

 private:
  cv::Vec3f bilinear(const cv::Mat& image, const cv::Vec2f& uv) const;
  std::vector<cv::Mat> levels_;  // CV_32FC3
};

}  // namespace omninav::sim
