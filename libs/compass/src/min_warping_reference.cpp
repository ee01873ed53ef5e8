// Min-warping, the exhaustive reference (min_warping.hpp): written from the equations with plain
// loops and sharing no code with the fast implementation, so that a test comparing the two
// checks the fast one's tables, index arithmetic and vector minima. For every grid (α, ψ),
// every snapshot column and every sampled ν it computes the partner column, the scale and the
// column distance from the pixels (memoised per column pair and plane).
#include <cmath>
#include <limits>
#include <vector>

#include "omninav/compass/min_warping.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::compass {

namespace {

constexpr double kTwoPi = 6.28318530717958647692;

double wrapped(double angle) {
  angle = std::fmod(angle, kTwoPi);
  if (angle > kTwoPi / 2) angle -= kTwoPi;
  if (angle <= -kTwoPi / 2) angle += kTwoPi;
  return angle;
}

// The panorama in grey (the channels' mean), averaged over blocks to width × height, as doubles
// row-major. Throws InputError for what min-warping cannot use.
std::vector<double> reduce(const cv::Mat& image, int width, int height, const char* name) {
  if (image.empty() || (image.depth() != CV_8U && image.depth() != CV_32F) ||
      (image.channels() != 1 && image.channels() != 3) || image.cols % width != 0 ||
      image.rows % height != 0) {
    throw InputError(std::string(name) + ": not a panorama the min-warping reference can use");
  }
  const int bw = image.cols / width, bh = image.rows / height, channels = image.channels();
  std::vector<double> out(static_cast<std::size_t>(width) * height, 0.0);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      double value = 0.0;
      for (int ch = 0; ch < channels; ++ch) {
        value += image.depth() == CV_8U ? image.ptr<unsigned char>(y)[x * channels + ch]
                                        : image.ptr<float>(y)[x * channels + ch];
      }
      if (!std::isfinite(value)) throw InputError(std::string(name) + ": non-finite pixels");
      out[static_cast<std::size_t>(y / bh) * width + x / bw] += value / channels / (bw * bh);
    }
  }
  return out;
}

}  // namespace

MinWarpingResult min_warping_reference(const cv::Mat& first, const cv::Mat& second,
                                       const MinWarpingParams& params,
                                       const PanoramaGeometry& geometry, cv::Mat* cost_surface) {
  params.check();
  if (first.size() != second.size()) {
    throw InputError("second panorama: its size differs from the first panorama's");
  }
  const int w = params.search_width_px, h = params.search_height_px;
  const std::vector<double> snapshot = reduce(first, w, h, "first panorama");
  const std::vector<double> current = reduce(second, w, h, "second panorama");
  const int planes = params.scale_planes, unit = planes / 2;
  const double row_step = (geometry.elevation_max_rad - geometry.elevation_min_rad) / h;

  // Column c of `image`, magnified about the horizon by `m` ≥ 1: row r at elevation e takes the
  // value at elevation atan(tan e / m), linearly between rows.
  const auto column = [&](const std::vector<double>& image, int c, double m) {
    std::vector<double> out(h);
    for (int r = 0; r < h; ++r) {
      const double e = geometry.elevation_max_rad - (r + 0.5) * row_step;
      double source = (geometry.elevation_max_rad - std::atan(std::tan(e) / m)) / row_step - 0.5;
      if (source < 0.0) source = 0.0;
      if (source > h - 1.0) source = h - 1.0;
      const int r0 = static_cast<int>(source);
      const int r1 = r0 + 1 < h ? r0 + 1 : r0;
      const double t = source - r0;
      out[r] = (1.0 - t) * image[r0 * w + c] + t * image[r1 * w + c];
    }
    return out;
  };
  const auto distance = [&](const std::vector<double>& x, const std::vector<double>& y) {
    double mx = 0.0, my = 0.0;
    for (int r = 0; r < h; ++r) mx += x[r] / h, my += y[r] / h;
    double difference = 0.0, norms = 0.0;
    for (int r = 0; r < h; ++r) {
      difference += (x[r] - mx - y[r] + my) * (x[r] - mx - y[r] + my);
      norms += (x[r] - mx) * (x[r] - mx) + (y[r] - my) * (y[r] - my);
    }
    return norms > 1e-6 ? difference / norms : 1.0;
  };
  std::vector<double> memo(static_cast<std::size_t>(w) * w * planes,
                           std::numeric_limits<double>::quiet_NaN());
  const auto pair_distance = [&](int i, int j, int k) {
    double& slot = memo[(static_cast<std::size_t>(k) * w + i) * w + j];
    if (std::isnan(slot)) {
      const double scale = std::pow(params.max_scale, static_cast<double>(k - unit) / unit);
      slot = k >= unit ? distance(column(snapshot, i, scale), column(current, j, 1.0))
                       : distance(column(snapshot, i, 1.0), column(current, j, 1.0 / scale));
    }
    return slot;
  };

  cv::Mat surface(w, w, CV_64F);
  for (int a = 0; a < w; ++a) {
    for (int p = 0; p < w; ++p) {
      double total = 0.0;
      for (int i = 0; i < w; ++i) {
        const double u = wrapped(-kTwoPi * (i - a) / w);  // from the direction of travel
        double best = std::numeric_limits<double>::infinity();
        for (int n = 0; n < params.distance_samples; ++n) {
          const double nu = params.max_relative_distance * n / (params.distance_samples - 1);
          const double v = std::atan2(std::sin(u), std::cos(u) - nu);
          // v = −2π(j − p − a)/W: the current column j, as an offset from i + p.
          double offset = std::remainder(-v * w / kTwoPi - (i - a), w);
          const int delta = static_cast<int>(std::lround(offset));
          int k = unit;
          if (planes > 1) {
            const double sigma = 1.0 / std::sqrt(1.0 - 2.0 * nu * std::cos(u) + nu * nu);
            k = unit + static_cast<int>(
                           std::lround(std::log(sigma) / (std::log(params.max_scale) / unit)));
            k = k < 0 ? 0 : (k >= planes ? planes - 1 : k);
          }
          const int j = ((i + p + delta) % w + w) % w;
          const double d = pair_distance(i, j, k);
          if (d < best) best = d;
        }
        total += best;
      }
      surface.at<double>(a, p) = total / w;
    }
  }
  if (cost_surface != nullptr) *cost_surface = surface.clone();

  // Featureless: zero-mean columns against those a quarter turn away, RMS in grey levels.
  const auto contrast = [&](const std::vector<double>& image) {
    double sum = 0.0;
    for (int c = 0; c < w; ++c) {
      const std::vector<double> x = column(image, c, 1.0);
      const std::vector<double> y = column(image, (c + w / 4) % w, 1.0);
      double mx = 0.0, my = 0.0;
      for (int r = 0; r < h; ++r) mx += x[r] / h, my += y[r] / h;
      for (int r = 0; r < h; ++r) sum += (x[r] - mx - y[r] + my) * (x[r] - mx - y[r] + my);
    }
    return std::sqrt(sum / (static_cast<double>(w) * h));
  };
  MinWarpingResult result;
  if (contrast(snapshot) < params.featureless_below_grey ||
      contrast(current) < params.featureless_below_grey) {
    result.featureless = true;
    return result;
  }
  int best_a = 0, best_p = 0;
  for (int a = 0; a < w; ++a) {
    for (int p = 0; p < w; ++p) {
      if (surface.at<double>(a, p) < surface.at<double>(best_a, best_p)) best_a = a, best_p = p;
    }
  }
  const auto cost = [&](int a, int p) { return surface.at<double>((a + w) % w, (p + w) % w); };
  const auto vertex = [](double left, double middle, double right) {
    const double c = left + right - 2.0 * middle;
    if (c <= 0.0) return 0.0;
    const double x = (left - right) / (2.0 * c);
    return x < -0.5 ? -0.5 : (x > 0.5 ? 0.5 : x);
  };
  const double p_fine =
      best_p + vertex(cost(best_a, best_p - 1), cost(best_a, best_p), cost(best_a, best_p + 1));
  const double a_fine =
      best_a + vertex(cost(best_a - 1, best_p), cost(best_a, best_p), cost(best_a + 1, best_p));
  double only = std::numeric_limits<double>::infinity();
  int only_p = 0;
  for (int p = 0; p < w; ++p) {
    double total = 0.0;
    for (int i = 0; i < w; ++i) total += pair_distance(i, (i + p) % w, unit);
    if (total / w < only) only = total / w, only_p = p;
  }
  // Search column a's block is centred on full column a·f + (f − 1)/2, f = W/w; column c of a
  // panorama W wide looks along π/2 − 2πc/W.
  const double f = static_cast<double>(first.cols) / w;
  result.travel_index = best_a;
  result.rotation_index = best_p;
  result.cost = cost(best_a, best_p);
  result.rotation_only_cost = only;
  result.rotation_only_rad = wrapped(kTwoPi * only_p / w);
  result.rotation_rad = wrapped(kTwoPi * p_fine / w);
  result.travel_rad = wrapped(kTwoPi / 4 - kTwoPi * (a_fine * f + (f - 1.0) / 2.0) / first.cols);
  result.home_rad = wrapped(result.travel_rad + kTwoPi / 2 - result.rotation_rad);
  return result;
}

}  // namespace omninav::compass
