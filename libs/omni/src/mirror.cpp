#include "omninav/omni/mirror.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "omninav/core/errors.hpp"
#include "omninav/core/statistics.hpp"

namespace omninav::omni {
namespace {

// Below this grey-level gap between the mean of the bright and the dark Otsu classes, the
// "disc" is noise, not a mirror on a darker surround.
constexpr double kMinContrast = 20.0;
// The mirror must cover at least this share of the image (and not all of it).
constexpr double kMinAreaShare = 0.005;
constexpr double kMaxForegroundShare = 0.97;
// Rim points further from the fitted circle than this share of its radius (RMS) mean the
// region is not a disc.
constexpr double kMaxRmsResidualShare = 0.05;
constexpr std::size_t kMinRimPoints = 20;

cv::Mat to_grey8(const cv::Mat& raw) {
  cv::Mat grey;
  switch (raw.channels()) {
    case 1:
      grey = raw;
      break;
    case 3:
      cv::cvtColor(raw, grey, cv::COLOR_BGR2GRAY);
      break;
    case 4:
      cv::cvtColor(raw, grey, cv::COLOR_BGRA2GRAY);
      break;
    default:
      throw InputError("find_mirror_circle: expected a 1-, 3- or 4-channel image, got " +
                       std::to_string(raw.channels()) + " channels");
  }
  if (grey.depth() == CV_8U) return grey;
  cv::Mat scaled;
  cv::normalize(grey, scaled, 0, 255, cv::NORM_MINMAX, CV_8U);
  return scaled;
}

struct Circle {
  cv::Point2d centre;
  double radius = 0.0;
};

// Algebraic (Kåsa) least-squares circle: x² + y² + D·x + E·y + F = 0, on coordinates taken
// relative to their mean for conditioning.
std::optional<Circle> fit_circle(const std::vector<cv::Point2d>& points) {
  if (points.size() < 3) return std::nullopt;
  cv::Point2d mean(0.0, 0.0);
  for (const cv::Point2d& point : points) mean += point;
  mean *= 1.0 / static_cast<double>(points.size());
  cv::Mat a(static_cast<int>(points.size()), 3, CV_64F);
  cv::Mat b(static_cast<int>(points.size()), 1, CV_64F);
  for (int i = 0; i < a.rows; ++i) {
    const double x = points[i].x - mean.x;
    const double y = points[i].y - mean.y;
    a.at<double>(i, 0) = x;
    a.at<double>(i, 1) = y;
    a.at<double>(i, 2) = 1.0;
    b.at<double>(i) = -(x * x + y * y);
  }
  cv::Mat solution;
  if (!cv::solve(a, b, solution, cv::DECOMP_SVD)) return std::nullopt;
  const double cx = -solution.at<double>(0) / 2.0;
  const double cy = -solution.at<double>(1) / 2.0;
  const double squared = cx * cx + cy * cy - solution.at<double>(2);
  if (!(squared > 0.0)) return std::nullopt;
  return Circle{{cx + mean.x, cy + mean.y}, std::sqrt(squared)};
}

// The bright disc of the mirror on its darker surround: Otsu's threshold of the smoothed
// image, cleaned; none when the two classes hardly differ or the bright one is too small or
// almost everything.
std::optional<cv::Mat> bright_disc_mask(const cv::Mat& grey) {
  const int min_side = std::min(grey.cols, grey.rows);
  // Smooth sensor noise and fine texture before thresholding; scale with the image.
  cv::Mat smooth;
  const double sigma = std::max(1.0, min_side / 600.0);
  cv::GaussianBlur(grey, smooth, cv::Size(0, 0), sigma);
  cv::Mat bright;
  const double threshold =
      cv::threshold(smooth, bright, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
  const double foreground_share = cv::countNonZero(bright) / static_cast<double>(bright.total());
  if (foreground_share < kMinAreaShare || foreground_share > kMaxForegroundShare) {
    return std::nullopt;
  }
  cv::Mat dark;
  cv::bitwise_not(bright, dark);
  const double contrast = cv::mean(smooth, bright)[0] - cv::mean(smooth, dark)[0];
  if (contrast < kMinContrast || threshold <= 0.0) return std::nullopt;
  // Remove specks, then close the gaps that dark texture on the mirror leaves near its rim.
  const int close_px = std::max(3, (min_side / 60) | 1);
  cv::morphologyEx(bright, bright, cv::MORPH_OPEN,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(3, 3)));
  cv::morphologyEx(bright, bright, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(close_px, close_px)));
  return bright;
}

// The rim of the largest bright region: its contour points not on the image border (a disc
// cropped by the image edges has straight border runs that are not its rim). Empty when the
// region is too small.
std::vector<cv::Point2d> rim_of_largest_region(cv::Mat& bright) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(bright, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  if (contours.empty()) return {};
  const auto largest = std::max_element(
      contours.begin(), contours.end(),
      [](const auto& a, const auto& b) { return cv::contourArea(a) < cv::contourArea(b); });
  if (cv::contourArea(*largest) < kMinAreaShare * static_cast<double>(bright.total())) return {};
  std::vector<cv::Point2d> rim;
  for (const cv::Point& point : *largest) {
    if (point.x > 0 && point.y > 0 && point.x < bright.cols - 1 && point.y < bright.rows - 1) {
      rim.emplace_back(point.x, point.y);
    }
  }
  return rim;
}

double distance_off(const Circle& circle, const cv::Point2d& point) {
  return std::hypot(point.x - circle.centre.x, point.y - circle.centre.y) - circle.radius;
}

// Fits, then refits without the points far off the circle (dents where dark texture touches
// the rim, bright things next to the mirror), robust to a minority of them. `rim` keeps the
// points of the last fit.
std::optional<Circle> robust_circle(std::vector<cv::Point2d>& rim) {
  std::optional<Circle> circle = fit_circle(rim);
  for (int pass = 0; pass < 2 && circle; ++pass) {
    std::vector<double> residuals;
    residuals.reserve(rim.size());
    for (const cv::Point2d& point : rim)
      residuals.push_back(std::abs(distance_off(*circle, point)));
    const double cutoff = std::max(1.5, 3.0 * 1.4826 * median(residuals));
    std::vector<cv::Point2d> kept;
    for (std::size_t i = 0; i < rim.size(); ++i) {
      if (residuals[i] <= cutoff) kept.push_back(rim[i]);
    }
    if (kept.size() < kMinRimPoints || kept.size() == rim.size()) break;
    rim = std::move(kept);
    circle = fit_circle(rim);
  }
  return circle;
}

double rms_distance_off(const Circle& circle, const std::vector<cv::Point2d>& rim) {
  double sum_squares = 0.0;
  for (const cv::Point2d& point : rim) {
    const double off = distance_off(circle, point);
    sum_squares += off * off;
  }
  return std::sqrt(sum_squares / static_cast<double>(rim.size()));
}

}  // namespace

std::optional<MirrorCircle> find_mirror_circle(const cv::Mat& raw) {
  if (raw.empty()) throw InputError("find_mirror_circle: the raw image is empty");
  const cv::Mat grey = to_grey8(raw);
  if (std::min(grey.cols, grey.rows) < 16) return std::nullopt;
  std::optional<cv::Mat> bright = bright_disc_mask(grey);
  if (!bright) return std::nullopt;
  std::vector<cv::Point2d> rim = rim_of_largest_region(*bright);
  if (rim.size() < kMinRimPoints) return std::nullopt;
  const std::optional<Circle> circle = robust_circle(rim);
  if (!circle || circle->radius < 4.0) return std::nullopt;
  if (rms_distance_off(*circle, rim) > kMaxRmsResidualShare * circle->radius) return std::nullopt;
  // The centre must lie in the image, or the "disc" is a bright corner or edge.
  if (circle->centre.x < 0.0 || circle->centre.y < 0.0 || circle->centre.x > grey.cols - 1.0 ||
      circle->centre.y > grey.rows - 1.0) {
    return std::nullopt;
  }
  // Contour points are the centres of the outermost bright pixels: the rim itself lies about
  // half a pixel further out.
  return MirrorCircle{circle->centre, circle->radius + 0.5};
}

}  // namespace omninav::omni
