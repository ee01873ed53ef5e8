#include "omninav/compass/travel_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "omninav/compass/distance.hpp"
#include "omninav/core/angles.hpp"

namespace omninav::compass {

TravelFit fit_turn_and_travel(const cv::Mat& first, const cv::Mat& second, const ColumnMask& mask,
                              double start_shift_px, const TravelFitParams& params) {
  const int width = first.cols;
  const int height = first.rows;
  const int channels = first.channels();
  const int row_step = std::max(1, height / std::max(1, params.rows_used));
  std::vector<int> columns;
  std::vector<double> sin_c, cos_c;
  for (int c = 0; c < width; ++c) {
    if (!mask.selected(c)) continue;
    columns.push_back(c);
    sin_c.push_back(std::sin(kTwoPi * c / width));
    cos_c.push_back(std::cos(kTwoPi * c / width));
  }
  Eigen::Vector3d p(start_shift_px, 0.0, 0.0);
  TravelFit fit;
  fit.shift_px = start_shift_px;
  double start_sse = -1.0, best_sse = -1.0;
  for (int iteration = 0; iteration <= params.iterations; ++iteration) {
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d gradient_sum = Eigen::Vector3d::Zero();
    double sse = 0.0;
    for (std::size_t i = 0; i < columns.size(); ++i) {
      const int c = columns[i];
      const Eigen::Vector3d v(1.0, sin_c[i], cos_c[i]);
      const double x = c - p.dot(v);
      const double lower = std::floor(x);
      const double f = x - lower;
      const int c0 = wrap_shift(static_cast<int>(lower), width);
      const int c1 = c0 + 1 == width ? 0 : c0 + 1;
      const int c_minus = c0 == 0 ? width - 1 : c0 - 1;
      const int c2 = c1 + 1 == width ? 0 : c1 + 1;
      double column_gg = 0.0, column_ge = 0.0;
      for (int r = 0; r < height; r += row_step) {
        const std::uint8_t* a = first.ptr<std::uint8_t>(r) + c * channels;
        const std::uint8_t* b = second.ptr<std::uint8_t>(r);
        for (int ch = 0; ch < channels; ++ch) {
          const double b0 = b[c0 * channels + ch], b1 = b[c1 * channels + ch];
          const double value = (1.0 - f) * b0 + f * b1;
          const double slope = 0.5 * ((1.0 - f) * (b1 - b[c_minus * channels + ch]) +
                                      f * (b[c2 * channels + ch] - b0));
          const double e = a[ch] - value;
          sse += e * e;
          column_gg += slope * slope;
          column_ge += slope * e;
        }
      }
      normal += column_gg * v * v.transpose();
      gradient_sum += column_ge * v;
    }
    if (iteration == 0) start_sse = sse;
    if (best_sse < 0.0 || sse < best_sse) {
      best_sse = sse;
      fit.shift_px = p(0);
      fit.parallax_sin_px = p(1);
      fit.parallax_cos_px = p(2);
    }
    if (iteration == params.iterations) break;
    // e(p + Δ) ≈ e + slope·vᵀΔ: the step that zeroes the linearised residual.
    const Eigen::Vector3d step = -normal.ldlt().solve(gradient_sum);
    if (!step.allFinite()) break;
    p += step.cwiseMax(-1.0).cwiseMin(1.0);
  }
  fit.improved = best_sse < start_sse;
  if (!fit.improved ||
      std::abs(fit.shift_px - start_shift_px) > params.max_correction_rad * width / kTwoPi) {
    fit = TravelFit{};
    fit.shift_px = start_shift_px;
  }
  return fit;
}

}  // namespace omninav::compass
