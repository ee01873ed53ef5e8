#include "omninav/compass/tilt.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "omninav/compass/frame.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/statistics.hpp"

namespace omninav::compass {
namespace {

constexpr double kTwoPi = 2.0 * 3.14159265358979323846;

void require_layout(const cv::Mat& panorama, const PanoramaGeometry& geometry,
                    const std::string& what) {
  require_panorama(panorama, what);
  if (panorama.cols != geometry.width_px || panorama.rows != geometry.height_px) {
    throw InputError(what + ": " + std::to_string(panorama.cols) + "x" +
                     std::to_string(panorama.rows) + " is not the panorama geometry's " +
                     std::to_string(geometry.width_px) + "x" + std::to_string(geometry.height_px));
  }
}

// Vertical profiles of `blocks` blocks of columns: profile b, row i is the mean grey (mean of
// the channels) of columns [edge(b) − offset, edge(b + 1) − offset) (mod W) in row i. Each
// block is at most two contiguous runs of bytes per row, summed as integers (vectorised).
std::vector<std::vector<double>> block_profiles(const cv::Mat& image, int blocks, int offset_px) {
  const int width = image.cols, height = image.rows, channels = image.channels();
  struct Run {
    int begin, end;  // bytes within a row
  };
  std::vector<std::array<Run, 2>> runs(static_cast<std::size_t>(blocks));
  std::vector<double> scale(static_cast<std::size_t>(blocks));
  const int shift = ((-offset_px) % width + width) % width;
  for (int b = 0; b < blocks; ++b) {
    const int begin = static_cast<int>(static_cast<long long>(b) * width / blocks);
    const int end = static_cast<int>(static_cast<long long>(b + 1) * width / blocks);
    const int source = (begin + shift) % width, length = end - begin;
    const int first_length = std::min(length, width - source);
    runs[static_cast<std::size_t>(b)] = {Run{source * channels, (source + first_length) * channels},
                                         Run{0, (length - first_length) * channels}};
    scale[static_cast<std::size_t>(b)] = 1.0 / (static_cast<double>(length) * channels);
  }
  std::vector<std::vector<double>> profiles(static_cast<std::size_t>(blocks),
                                            std::vector<double>(static_cast<std::size_t>(height)));
  for (int r = 0; r < height; ++r) {
    const std::uint8_t* row = image.ptr<std::uint8_t>(r);
    for (int b = 0; b < blocks; ++b) {
      std::uint32_t sum = 0;
      for (const Run& run : runs[static_cast<std::size_t>(b)]) {
        for (int k = run.begin; k < run.end; ++k) sum += row[k];
      }
      profiles[static_cast<std::size_t>(b)][static_cast<std::size_t>(r)] =
          sum * scale[static_cast<std::size_t>(b)];
    }
  }
  return profiles;
}

struct BlockShift {
  double shift_rows = 0.0;  // s: second(i) ≈ first(i − s)
  double weight = 0.0;      // vertical-gradient energy of the first's profile where compared
};

// Linear interpolation of `values` at fractional index x in [0, n − 1].
double interpolate(const std::vector<double>& values, double x) {
  const int n = static_cast<int>(values.size());
  const int low = std::clamp(static_cast<int>(std::floor(x)), 0, n - 2);
  const double t = x - low;
  return values[static_cast<std::size_t>(low)] * (1.0 - t) +
         values[static_cast<std::size_t>(low + 1)] * t;
}

// The row shift s that best explains second(i) = first(i − s): a search over whole shifts in
// [−max_shift, max_shift] (mean squared difference over the rows both cover), then Gauss-Newton
// steps on the linearly interpolated first profile.
BlockShift block_shift(const std::vector<double>& first, const std::vector<double>& second,
                       const std::vector<double>& gradient, int max_shift, int steps) {
  const int height = static_cast<int>(first.size());
  double best_cost = std::numeric_limits<double>::infinity();
  int best = 0;
  for (int s = -max_shift; s <= max_shift; ++s) {
    const int low = std::max(0, s), high = std::min(height, height + s);
    if (high - low < height / 2) continue;
    double cost = 0.0;
    for (int i = low; i < high; ++i) {
      const double d = second[static_cast<std::size_t>(i)] - first[static_cast<std::size_t>(i - s)];
      cost += d * d;
    }
    cost /= high - low;
    if (cost < best_cost) best_cost = cost, best = s;
  }
  BlockShift result;
  double s = best;
  for (int step = 0; step < steps; ++step) {
    double numerator = 0.0, energy = 0.0;
    for (int i = 0; i < height; ++i) {
      const double x = i - s;
      if (x < 0.0 || x > height - 1) continue;
      const double g = interpolate(gradient, x);
      numerator += (second[static_cast<std::size_t>(i)] - interpolate(first, x)) * -g;
      energy += g * g;
    }
    result.weight = energy;
    if (energy <= 0.0) break;
    const double update = std::clamp(numerator / energy, -1.0, 1.0);
    s = std::clamp(s + update, -max_shift - 1.0, max_shift + 1.0);
    if (std::abs(update) < 1e-3) break;
  }
  result.shift_rows = s;
  return result;
}

}  // namespace

TiltEstimate estimate_relative_tilt(const cv::Mat& first, const cv::Mat& second,
                                    const PanoramaGeometry& geometry, double second_shift_px,
                                    const TiltParams& params) {
  require_layout(first, geometry, "first panorama");
  require_layout(second, geometry, "second panorama");
  if (first.channels() != second.channels()) {
    throw InputError("the two panoramas differ in channels");
  }
  const int width = geometry.width_px, height = geometry.height_px;
  if (params.blocks < 4 || params.blocks > width) {
    throw UsageError("tilt blocks must be in [4, width], not " + std::to_string(params.blocks));
  }
  if (!(params.max_tilt_rad > 0.0) || params.refinement_steps < 0 || params.reweighting_steps < 0 ||
      !(params.outlier_rows > 0.0)) {
    throw UsageError("tilt parameters out of range");
  }
  const double rad_per_row = geometry.rad_per_row();
  const int max_shift =
      std::clamp(static_cast<int>(std::ceil(params.max_tilt_rad / rad_per_row)), 1, height / 2);
  const int offset = static_cast<int>(std::lround(second_shift_px));

  const auto first_profiles = block_profiles(first, params.blocks, 0);
  const auto second_profiles = block_profiles(second, params.blocks, offset);

  std::vector<double> delta_rad, weight, cos_azimuth, sin_azimuth;
  std::vector<double> gradient(static_cast<std::size_t>(height));
  for (int b = 0; b < params.blocks; ++b) {
    const auto& profile = first_profiles[static_cast<std::size_t>(b)];
    for (int i = 0; i < height; ++i) {
      const int up = std::max(0, i - 1), down = std::min(height - 1, i + 1);
      gradient[static_cast<std::size_t>(i)] =
          (profile[static_cast<std::size_t>(down)] - profile[static_cast<std::size_t>(up)]) /
          std::max(1, down - up);
    }
    const BlockShift shift = block_shift(profile, second_profiles[static_cast<std::size_t>(b)],
                                         gradient, max_shift, params.refinement_steps);
    // A minimum at the end of the searched range is no measurement.
    if (shift.weight <= 0.0 || std::abs(shift.shift_rows) > max_shift - 0.5) continue;
    // The block's centre column in the first, and where the second looks there.
    const double first_centre = (static_cast<double>(b) * width / params.blocks +
                                 static_cast<double>(b + 1) * width / params.blocks - 1.0) /
                                2.0;
    const double azimuth = azimuth_of_column(first_centre - second_shift_px, width);
    delta_rad.push_back(shift.shift_rows * rad_per_row);
    weight.push_back(shift.weight);
    cos_azimuth.push_back(std::cos(azimuth));
    sin_azimuth.push_back(std::sin(azimuth));
  }

  TiltEstimate estimate;
  const std::size_t n = delta_rad.size();
  std::vector<double> robust(n, 1.0);
  std::vector<double> residual(n, 0.0);
  for (int iteration = 0; iteration <= params.reweighting_steps; ++iteration) {
    // Weighted least squares of δ_b = −p·cos φ_b + r·sin φ_b.
    double a11 = 0.0, a12 = 0.0, a22 = 0.0, b1 = 0.0, b2 = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const double w = weight[k] * robust[k];
      const double x1 = -cos_azimuth[k], x2 = sin_azimuth[k];
      a11 += w * x1 * x1, a12 += w * x1 * x2, a22 += w * x2 * x2;
      b1 += w * x1 * delta_rad[k], b2 += w * x2 * delta_rad[k];
    }
    const double determinant = a11 * a22 - a12 * a12;
    if (!(determinant > 1e-12 * (a11 + a22) * (a11 + a22))) return TiltEstimate{};
    estimate.pitch_rad = (a22 * b1 - a12 * b2) / determinant;
    estimate.roll_rad = (a11 * b2 - a12 * b1) / determinant;
    for (std::size_t k = 0; k < n; ++k) {
      residual[k] = (delta_rad[k] -
                     (-estimate.pitch_rad * cos_azimuth[k] + estimate.roll_rad * sin_azimuth[k])) /
                    rad_per_row;
    }
    if (iteration == params.reweighting_steps) break;
    std::vector<double> magnitudes(n);
    for (std::size_t k = 0; k < n; ++k) magnitudes[k] = std::abs(residual[k]);
    const double scale = std::max(params.outlier_rows, 4.685 * 1.4826 * median(magnitudes));
    for (std::size_t k = 0; k < n; ++k) {
      const double u = residual[k] / scale;
      robust[k] = std::abs(u) < 1.0 ? (1.0 - u * u) * (1.0 - u * u) : 0.0;
    }
  }
  double sum_w = 0.0, sum_wr = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double w = weight[k] * robust[k];
    if (w > 0.0) ++estimate.blocks_used;
    sum_w += w, sum_wr += w * residual[k] * residual[k];
  }
  estimate.residual_rows = sum_w > 0.0 ? std::sqrt(sum_wr / sum_w) : 0.0;
  return estimate;
}

cv::Mat level_panorama(const cv::Mat& panorama, const PanoramaGeometry& geometry, double pitch_rad,
                       double roll_rad) {
  require_layout(panorama, geometry, "panorama");
  if (pitch_rad == 0.0 && roll_rad == 0.0) return panorama.clone();
  const int width = geometry.width_px, height = geometry.height_px;
  // The level pixel looking along v shows what the tilted camera's pixel looking along Rᵀ·v
  // shows, R = Ry(pitch)·Rx(roll) (the renderer's tilt in the robot's frame). The source pixel
  // is exact on a grid of every `step` columns and rows and bilinear in between (the map is
  // smooth: its second derivative is of the order of the tilt times the grid spacing squared).
  const double cp = std::cos(pitch_rad), sp = std::sin(pitch_rad);
  const double cr = std::cos(roll_rad), sr = std::sin(roll_rad);
  const cv::Matx33d rotation =
      cv::Matx33d(cp, 0, sp, 0, 1, 0, -sp, 0, cp) * cv::Matx33d(1, 0, 0, 0, cr, -sr, 0, sr, cr);
  const cv::Matx33d inverse = rotation.t();
  constexpr int step = 8;
  const int grid_columns = (width + step - 1) / step + 1,
            grid_rows = (height + step - 1) / step + 1;
  cv::Mat grid_dx(grid_rows, grid_columns, CV_64F), grid_y(grid_rows, grid_columns, CV_64F);
  for (int gr = 0; gr < grid_rows; ++gr) {
    const double row = static_cast<double>(gr) * step;
    const double elevation = geometry.elevation_of_row(row);
    for (int gc = 0; gc < grid_columns; ++gc) {
      const double column = gc * step;
      const double azimuth = azimuth_of_column(column, width);
      const cv::Vec3d v(std::cos(elevation) * std::cos(azimuth),
                        std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
      const cv::Vec3d u = inverse * v;
      const double source_azimuth = std::atan2(u[1], u[0]);
      double dx = (azimuth - source_azimuth) * width / kTwoPi;  // columns grow as azimuth falls
      dx -= width * std::round(dx / width);
      grid_dx.at<double>(gr, gc) = dx;
      grid_y.at<double>(gr, gc) = geometry.row_of_elevation(std::asin(std::clamp(u[2], -1.0, 1.0)));
    }
  }
  // Source columns stay within ±pad of their own column: the tilt's azimuth change is at most
  // about |tilt|·|tan elevation|.
  double max_dx = 0.0;
  for (int k = 0; k < grid_dx.rows * grid_dx.cols; ++k) {
    max_dx = std::max(max_dx, std::abs(grid_dx.at<double>(k)));
  }
  const int pad = static_cast<int>(std::ceil(max_dx)) + 2;
  cv::Mat padded;
  cv::copyMakeBorder(panorama, padded, 0, 0, pad, pad, cv::BORDER_WRAP);
  // The grid interpolated to each row first, then along the row.
  cv::Mat map_x(height, width, CV_32F), map_y(height, width, CV_32F);
  std::vector<float> line_dx(static_cast<std::size_t>(grid_columns)),
      line_y(static_cast<std::size_t>(grid_columns));
  for (int r = 0; r < height; ++r) {
    const int gr = r / step;
    const double tr = static_cast<double>(r - gr * step) / step;
    for (int gc = 0; gc < grid_columns; ++gc) {
      line_dx[static_cast<std::size_t>(gc)] = static_cast<float>(
          (1.0 - tr) * grid_dx.at<double>(gr, gc) + tr * grid_dx.at<double>(gr + 1, gc));
      line_y[static_cast<std::size_t>(gc)] = static_cast<float>(
          (1.0 - tr) * grid_y.at<double>(gr, gc) + tr * grid_y.at<double>(gr + 1, gc));
    }
    float* mx = map_x.ptr<float>(r);
    float* my = map_y.ptr<float>(r);
    for (int gc = 0; gc + 1 < grid_columns; ++gc) {
      const std::size_t g = static_cast<std::size_t>(gc);
      const int begin = gc * step, end = std::min(width, begin + step);
      const float x0 = static_cast<float>(begin + pad) + line_dx[g];
      const float x_slope = 1.0f + (line_dx[g + 1] - line_dx[g]) / step;
      const float y_slope = (line_y[g + 1] - line_y[g]) / step;
      for (int c = begin; c < end; ++c) {
        const float k = static_cast<float>(c - begin);
        mx[c] = x0 + k * x_slope;
        my[c] = line_y[g] + k * y_slope;
      }
    }
  }
  cv::Mat levelled;
  cv::remap(padded, levelled, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return levelled;
}

TurnAndTilt match_levelled(const PairMatcher& matcher, const cv::Mat& first, const cv::Mat& second,
                           const PanoramaGeometry& geometry, const TiltParams& params, int rounds) {
  if (rounds < 1) throw UsageError("match_levelled needs at least one round");
  const CompassFrame first_frame(first);
  TurnAndTilt result;
  result.match = matcher.match(first_frame, CompassFrame(second));
  for (int round = 0; round < rounds; ++round) {
    result.tilt =
        estimate_relative_tilt(first, second, geometry, result.match.subpixel_shift_px, params);
    result.levelled = level_panorama(second, geometry, result.tilt.pitch_rad, result.tilt.roll_rad);
    result.match = matcher.match(first_frame, CompassFrame(result.levelled), result.match.shift_px);
  }
  return result;
}

}  // namespace omninav::compass
