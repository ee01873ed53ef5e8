#pragma once
// Images with known content for the unwrapping tests: a smooth textured panorama (a cylinder
// "scene" defined in azimuth, so the same scene at any width), Gaussian spots at exact raw
// positions, and comparison helpers.

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

#include "omninav/core/angles.hpp"

namespace omninav::omni::testing {

// A W×H BGR panorama of smooth periodic gradients plus a few blobs at irregular azimuths (so
// that no roll but the right one matches it). Its finest detail (blobs of σ 3.4°, ripples of
// 20° period) spans several columns and about 4 rows (a
// few raw pixels even at the inner ring of the tests' annuli, so interpolation errs little),
// fine enough that a panorama one column off differs by 2.4 grey levels on average (W = 360).
// Values stay within [`low`, `high`].
inline cv::Mat textured_panorama(int width_px, int height_px, double low = 20.0,
                                 double high = 235.0) {
  struct Blob {
    double theta_rad;
    double row_share;  // 0 top, 1 bottom
    double amplitude;
  };
  const std::vector<Blob> blobs = {{0.3, 0.3, 1.0},  {1.9, 0.7, -0.9}, {2.6, 0.4, 0.8},
                                   {4.0, 0.2, -1.0}, {4.4, 0.8, 0.9},  {5.7, 0.5, 0.7},
                                   {1.1, 0.5, 0.8},  {3.3, 0.6, -0.8}};
  cv::Mat panorama(height_px, width_px, CV_8UC3);
  for (int row = 0; row < height_px; ++row) {
    const double v = (row + 0.5) / height_px;
    for (int column = 0; column < width_px; ++column) {
      const double theta = kTwoPi * column / width_px;
      double channel_values[3];
      for (int channel = 0; channel < 3; ++channel) {
        double value = 0.3 * std::sin(theta + 1.3 * channel) +
                       0.15 * std::cos(3.0 * theta - 2.0 * v + 0.7 * channel) +
                       0.15 * std::sin(2.0 * kPi * v + 0.5 * channel) +
                       0.15 * std::sin(18.0 * theta + 9.0 * v + 0.9 * channel) *
                           std::cos(5.0 * theta - 1.1 * channel);
        for (const Blob& blob : blobs) {
          const double d_theta = std::remainder(theta - blob.theta_rad, kTwoPi);
          const double d_v = v - blob.row_share;
          value += 0.3 * blob.amplitude *
                   std::exp(-(d_theta * d_theta) / (2.0 * 0.06 * 0.06) -
                            (d_v * d_v) / (2.0 * 0.1 * 0.1));
        }
        // value lies in about [−1, 1]
        const double scaled = low + (high - low) * (0.5 + 0.5 * std::clamp(value, -1.0, 1.0));
        channel_values[channel] = scaled;
      }
      panorama.at<cv::Vec3b>(row, column) = cv::Vec3b(cv::saturate_cast<uchar>(channel_values[0]),
                                                      cv::saturate_cast<uchar>(channel_values[1]),
                                                      cv::saturate_cast<uchar>(channel_values[2]));
    }
  }
  return panorama;
}

// Adds a Gaussian spot of peak `peak` and standard deviation `sigma_px` centred at `at`
// (OpenCV pixel coordinates) to a 1-channel 8-bit image.
inline void add_spot(cv::Mat& grey, cv::Point2d at, double sigma_px = 2.0, double peak = 250.0) {
  const int reach = static_cast<int>(std::ceil(4.0 * sigma_px));
  for (int y = static_cast<int>(at.y) - reach; y <= static_cast<int>(at.y) + reach; ++y) {
    for (int x = static_cast<int>(at.x) - reach; x <= static_cast<int>(at.x) + reach; ++x) {
      if (x < 0 || y < 0 || x >= grey.cols || y >= grey.rows) continue;
      const double d2 = (x - at.x) * (x - at.x) + (y - at.y) * (y - at.y);
      const double value =
          grey.at<uchar>(y, x) + peak * std::exp(-d2 / (2.0 * sigma_px * sigma_px));
      grey.at<uchar>(y, x) = cv::saturate_cast<uchar>(value);
    }
  }
}

// The column where a 1-channel panorama's brightness concentrates: the circular mean of the
// column index weighted by the column sums (a spot near column 0 straddles the seam).
inline double bright_column(const cv::Mat& grey_panorama) {
  cv::Mat sums;
  cv::reduce(grey_panorama, sums, 0, cv::REDUCE_SUM, CV_64F);
  const int width = grey_panorama.cols;
  double s = 0.0;
  double c = 0.0;
  for (int column = 0; column < width; ++column) {
    const double theta = kTwoPi * column / width;
    s += sums.at<double>(column) * std::sin(theta);
    c += sums.at<double>(column) * std::cos(theta);
  }
  double mean = std::atan2(s, c) * width / kTwoPi;
  if (mean < 0.0) mean += width;
  return mean;
}

// The row where a 1-channel panorama's brightness concentrates (weighted mean).
inline double bright_row(const cv::Mat& grey_panorama) {
  cv::Mat sums;
  cv::reduce(grey_panorama, sums, 1, cv::REDUCE_SUM, CV_64F);
  double total = 0.0;
  double weighted = 0.0;
  for (int row = 0; row < grey_panorama.rows; ++row) {
    total += sums.at<double>(row);
    weighted += row * sums.at<double>(row);
  }
  return weighted / total;
}

// Signed circular difference a − b of two columns, in (−W/2, W/2].
inline double column_difference(double a, double b, int width_px) {
  double d = std::remainder(a - b, static_cast<double>(width_px));
  if (d <= -width_px / 2.0) d += width_px;
  return d;
}

// Mean absolute difference per pixel and channel, in grey levels.
inline double mean_abs_error(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat difference;
  cv::absdiff(a, b, difference);
  const cv::Scalar sums = cv::sum(difference);
  double total = 0.0;
  for (int channel = 0; channel < a.channels(); ++channel) total += sums[channel];
  return total / (static_cast<double>(a.total()) * a.channels());
}

}  // namespace omninav::omni::testing
