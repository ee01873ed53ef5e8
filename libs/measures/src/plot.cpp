#include "omninav/measures/plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <string>

#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/measures/hershey_text.hpp"
#include "omninav/measures/png.hpp"

namespace omninav::measures {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kTitleScale = 0.7;
constexpr double kLabelScale = 0.55;
constexpr double kTickScale = 0.45;
constexpr int kShift = 4;  // sub-pixel bits for cv::line / cv::circle coordinates
constexpr double kSubpixel = 1 << kShift;

// Margins around the plot area, in pixels: room for the title (top), the tick labels and the
// axis labels (left, bottom).
constexpr int kMarginLeft = 85;
constexpr int kMarginRight = 25;
constexpr int kMarginTop = 45;
constexpr int kMarginBottom = 65;
// About one tick per this many pixels.
constexpr int kPxPerTickX = 110;
constexpr int kPxPerTickY = 70;

const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kText(30, 30, 30);
const cv::Scalar kFrame(60, 60, 60);
const cv::Scalar kGrid(228, 228, 228);
const cv::Scalar kZeroLine(90, 90, 90);
const cv::Scalar kLegendBorder(170, 170, 170);

cv::Point subpixel(cv::Point2d p) {
  return {cvRound(p.x * kSubpixel), cvRound(p.y * kSubpixel)};
}

void require_plot_size(cv::Size size_px) {
  if (size_px.width < 300 || size_px.height < 200) {
    throw UsageError("plot size " + std::to_string(size_px.width) + "x" +
                     std::to_string(size_px.height) + " px is too small (at least 300x200)");
  }
}

enum class Align { kLeft, kCentre, kRight };

// Draws `text` with its vertical centre at anchor.y, aligned on anchor.x as asked.
void draw_text(cv::Mat& image, const std::string& text, cv::Point anchor, double scale, Align align,
               int thickness = 1, const cv::Scalar& colour = kText) {
  const std::string ascii = hershey_text(text);
  int baseline = 0;
  const cv::Size size = cv::getTextSize(ascii, kFont, scale, thickness, &baseline);
  int x = anchor.x;
  if (align == Align::kCentre) x -= size.width / 2;
  if (align == Align::kRight) x -= size.width;
  cv::putText(image, ascii, cv::Point(x, anchor.y + size.height / 2), kFont, scale, colour,
              thickness, cv::LINE_AA);
}

// Draws `text` turned a quarter counter-clockwise (read bottom to top), centred on `centre`.
// putText cannot rotate, so the text is drawn on a white strip that is rotated and copied in.
void draw_vertical_text(cv::Mat& image, const std::string& text, cv::Point centre, double scale) {
  if (text.empty()) return;
  const std::string ascii = hershey_text(text);
  int baseline = 0;
  const cv::Size size = cv::getTextSize(ascii, kFont, scale, 1, &baseline);
  cv::Mat strip(size.height + baseline + 4, size.width + 4, CV_8UC3, kWhite);
  cv::putText(strip, ascii, cv::Point(2, size.height + 2), kFont, scale, kText, 1, cv::LINE_AA);
  cv::Mat rotated;
  cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  const cv::Rect target(centre.x - rotated.cols / 2, centre.y - rotated.rows / 2, rotated.cols,
                        rotated.rows);
  const cv::Rect clipped = target & cv::Rect(0, 0, image.cols, image.rows);
  if (clipped.empty()) return;
  rotated(cv::Rect(clipped.x - target.x, clipped.y - target.y, clipped.width, clipped.height))
      .copyTo(image(clipped));
}

// A tick value printed with as many decimals as the step needs (steps are 1, 2 or 5 × 10^k).
std::string format_tick(double value, double step) {
  if (std::abs(value) < step * 1e-9) value = 0.0;  // no "-0"
  const double magnitude = std::max(std::abs(value), step);
  if (magnitude >= 1e6 || step < 1e-4) return general(value, 3);
  return fixed(value, std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9))));
}

// The plot area in pixels and the data ranges it shows.
struct Frame {
  cv::Rect area;
  double x_low = 0.0, x_high = 1.0, y_low = 0.0, y_high = 1.0;

  cv::Point2d to_pixel(double x, double y) const {
    return {area.x + (x - x_low) / (x_high - x_low) * (area.width - 1),
            area.y + (y_high - y) / (y_high - y_low) * (area.height - 1)};
  }
};

cv::Rect plot_area(cv::Size size_px) {
  return {kMarginLeft, kMarginTop, size_px.width - kMarginLeft - kMarginRight,
          size_px.height - kMarginTop - kMarginBottom};
}

struct Bounds {
  double x_low = std::numeric_limits<double>::infinity();
  double x_high = -std::numeric_limits<double>::infinity();
  double y_low = std::numeric_limits<double>::infinity();
  double y_high = -std::numeric_limits<double>::infinity();

  void add(double x, double y) {
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    x_low = std::min(x_low, x);
    x_high = std::max(x_high, x);
    y_low = std::min(y_low, y);
    y_high = std::max(y_high, y);
  }
  bool empty() const { return x_low > x_high; }
};

// Grid lines and labelled ticks (only those within the frame), then the title and axis labels.
void draw_axes_background(cv::Mat& image, const Frame& frame, const std::vector<double>& x_ticks,
                          const std::vector<double>& y_ticks) {
  for (double x : x_ticks) {
    if (x < frame.x_low || x > frame.x_high) continue;
    const int px = cvRound(frame.to_pixel(x, 0.0).x);
    cv::line(image, {px, frame.area.y}, {px, frame.area.br().y - 1}, kGrid, 1, cv::LINE_8);
  }
  for (double y : y_ticks) {
    if (y < frame.y_low || y > frame.y_high) continue;
    const int py = cvRound(frame.to_pixel(0.0, y).y);
    cv::line(image, {frame.area.x, py}, {frame.area.br().x - 1, py}, kGrid, 1, cv::LINE_8);
  }
}

void draw_axes_foreground(cv::Mat& image, const Frame& frame, const std::vector<double>& x_ticks,
                          const std::vector<double>& y_ticks, const std::string& title,
                          const std::string& x_label, const std::string& y_label) {
  cv::rectangle(image, frame.area, kFrame, 1, cv::LINE_8);
  const int bottom = frame.area.br().y - 1;
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1.0;
  for (double x : x_ticks) {
    if (x < frame.x_low || x > frame.x_high) continue;
    const int px = cvRound(frame.to_pixel(x, 0.0).x);
    cv::line(image, {px, bottom}, {px, bottom + 5}, kFrame, 1, cv::LINE_8);
    draw_text(image, format_tick(x, x_step), {px, bottom + 17}, kTickScale, Align::kCentre);
  }
  const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1.0;
  for (double y : y_ticks) {
    if (y < frame.y_low || y > frame.y_high) continue;
    const int py = cvRound(frame.to_pixel(0.0, y).y);
    cv::line(image, {frame.area.x - 5, py}, {frame.area.x, py}, kFrame, 1, cv::LINE_8);
    draw_text(image, format_tick(y, y_step), {frame.area.x - 8, py}, kTickScale, Align::kRight);
  }
  const int centre_x = frame.area.x + frame.area.width / 2;
  draw_text(image, title, {centre_x, kMarginTop / 2}, kTitleScale, Align::kCentre, 2);
  draw_text(image, x_label, {centre_x, image.rows - 18}, kLabelScale, Align::kCentre);
  draw_vertical_text(image, y_label, {16, frame.area.y + frame.area.height / 2}, kLabelScale);
}

struct LegendEntry {
  std::string name;
  cv::Scalar colour;
  bool line = true;     // a short line as its swatch
  bool marker = false;  // a dot as its swatch
};

// The legend in the top-right corner of the plot area, on white with a light border.
void draw_legend(cv::Mat& image, const Frame& frame, const std::vector<LegendEntry>& entries) {
  if (entries.empty()) return;
  constexpr int kRow = 20;
  constexpr int kSwatch = 28;
  int text_width = 0;
  for (const LegendEntry& entry : entries) {
    int baseline = 0;
    text_width =
        std::max(text_width,
                 cv::getTextSize(hershey_text(entry.name), kFont, kTickScale, 1, &baseline).width);
  }
  const int width = kSwatch + text_width + 24;
  const int height = static_cast<int>(entries.size()) * kRow + 10;
  const cv::Rect box(frame.area.br().x - width - 8, frame.area.y + 8, width, height);
  cv::rectangle(image, box, kWhite, cv::FILLED);
  cv::rectangle(image, box, kLegendBorder, 1, cv::LINE_8);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const int y = box.y + 5 + kRow / 2 + static_cast<int>(i) * kRow;
    const int x = box.x + 8;
    if (entries[i].line) {
      cv::line(image, {x, y}, {x + kSwatch, y}, entries[i].colour, 2, cv::LINE_AA);
    }
    if (entries[i].marker) {
      cv::circle(image, {x + kSwatch / 2, y}, 4, entries[i].colour, cv::FILLED, cv::LINE_AA);
    }
    draw_text(image, entries[i].name, {x + kSwatch + 8, y}, kTickScale, Align::kLeft);
  }
}

// A step of nice·10^exponent, nice in {1, 2, 5}. Tick k is computed as k·nice/10^−exponent
// for negative exponents (10^n is exact for the n that occur), so that tick 3 of step 0.2 is
// the double nearest 0.6, as typed, rather than 3 × 0.2 = 0.6000000000000001.
struct TickStep {
  double nice = 1.0;
  int exponent = 0;

  double value() const {
    return exponent >= 0 ? nice * std::pow(10.0, exponent) : nice / std::pow(10.0, -exponent);
  }
  double tick(double k) const {
    return exponent >= 0 ? k * nice * std::pow(10.0, exponent)
                         : k * nice / std::pow(10.0, -exponent);
  }
};

TickStep nice_step(double range, int intervals) {
  const double raw_step = range / std::max(1, intervals);
  const int exponent = static_cast<int>(std::floor(std::log10(raw_step)));
  const double residual = raw_step / std::pow(10.0, exponent);
  TickStep step;
  step.exponent = exponent;
  step.nice = residual <= 1.0 ? 1.0 : residual <= 2.0 ? 2.0 : residual <= 5.0 ? 5.0 : 10.0;
  if (step.nice == 10.0) {
    step.nice = 1.0;
    ++step.exponent;
  }
  return step;
}

// Ticks k·step for k = first, first + 1, ..., last, counted in whole numbers: for bounds so far
// from 0 that k + 1 == k in floating point, a loop over k would never end.
std::vector<double> ticks_from(double first, double last, const TickStep& step) {
  constexpr double kMaxTicks = 1000.0;
  if (!(last - first <= kMaxTicks)) {
    throw UsageError(fmt::format("an axis from {} to {} would have more than {} ticks",
                                 general(first * step.value()), general(last * step.value()),
                                 general(kMaxTicks)));
  }
  std::vector<double> ticks;
  const int count = last >= first ? static_cast<int>(last - first) + 1 : 0;
  for (int i = 0; i < count; ++i) ticks.push_back(step.tick(first + i));
  return ticks;
}

// Multiples of `step` within [low, high].
std::vector<double> ticks_within(double low, double high, const TickStep& step) {
  return ticks_from(std::ceil(low / step.value() - 1e-9), std::floor(high / step.value() + 1e-9),
                    step);
}

// Equal scales: one data unit per the same number of pixels on both axes, the data centred,
// with 5 % of the larger extent as padding so that points on the edge are not cut.
Frame equal_scale_frame(const Bounds& bounds, cv::Size size_px) {
  Frame frame;
  frame.area = plot_area(size_px);
  double extent = std::max(bounds.x_high - bounds.x_low, bounds.y_high - bounds.y_low);
  if (extent <= 0.0) extent = std::max(1.0, std::abs(bounds.x_low) + std::abs(bounds.y_low));
  const double padded_w = bounds.x_high - bounds.x_low + 0.1 * extent;
  const double padded_h = bounds.y_high - bounds.y_low + 0.1 * extent;
  const double units_per_px =
      std::max(padded_w / (frame.area.width - 1), padded_h / (frame.area.height - 1));
  const double centre_x = 0.5 * (bounds.x_low + bounds.x_high);
  const double centre_y = 0.5 * (bounds.y_low + bounds.y_high);
  frame.x_low = centre_x - 0.5 * units_per_px * (frame.area.width - 1);
  frame.x_high = centre_x + 0.5 * units_per_px * (frame.area.width - 1);
  frame.y_low = centre_y - 0.5 * units_per_px * (frame.area.height - 1);
  frame.y_high = centre_y + 0.5 * units_per_px * (frame.area.height - 1);
  return frame;
}

// A segment of grey `level` from a to b (pixels), opaque or translucent (`alpha` < 1): the
// line's coverage drawn into a mask over its bounding box, then image ← image·(1 − α·m) +
// level·α·m only there.
void draw_segment(cv::Mat& image, const cv::Point2d& a, const cv::Point2d& b, double level,
                  double alpha) {
  if (alpha >= 1.0) {
    cv::line(image, subpixel(a), subpixel(b), cv::Scalar::all(level), 1, cv::LINE_AA, kShift);
    return;
  }
  const cv::Rect box =
      cv::Rect(cv::Point(cvFloor(std::min(a.x, b.x)) - 2, cvFloor(std::min(a.y, b.y)) - 2),
               cv::Point(cvCeil(std::max(a.x, b.x)) + 3, cvCeil(std::max(a.y, b.y)) + 3)) &
      cv::Rect(0, 0, image.cols, image.rows);
  if (box.empty()) return;
  cv::Mat mask = cv::Mat::zeros(box.size(), CV_8U);
  const cv::Point2d offset(box.x, box.y);
  cv::line(mask, subpixel(a - offset), subpixel(b - offset), cv::Scalar(255), 1, cv::LINE_AA,
           kShift);
  cv::Mat roi = image(box);
  for (int r = 0; r < roi.rows; ++r) {
    const uchar* m = mask.ptr<uchar>(r);
    cv::Vec3b* pixel = roi.ptr<cv::Vec3b>(r);
    for (int c = 0; c < roi.cols; ++c) {
      if (m[c] == 0) continue;
      const double weight = alpha * m[c] / 255.0;
      for (int k = 0; k < 3; ++k) {
        pixel[c][k] = cv::saturate_cast<uchar>(pixel[c][k] * (1.0 - weight) + level * weight);
      }
    }
  }
}

}  // namespace

cv::Scalar palette_colour(std::size_t index) {
  // Tableau 10, as BGR.
  static const std::array<cv::Scalar, 10> kPalette = {
      cv::Scalar(180, 119, 31),  cv::Scalar(14, 127, 255),  cv::Scalar(44, 160, 44),
      cv::Scalar(40, 39, 214),   cv::Scalar(189, 103, 148), cv::Scalar(75, 86, 140),
      cv::Scalar(194, 119, 227), cv::Scalar(127, 127, 127), cv::Scalar(34, 189, 188),
      cv::Scalar(207, 190, 23)};
  return kPalette[index % kPalette.size()];
}

std::vector<double> nice_ticks(double low, double high, int target_count) {
  if (!std::isfinite(low) || !std::isfinite(high) || low > high) {
    // %g: DBL_MAX in 12 characters, not 309 digits
    throw UsageError(
        fmt::format("axis range [{}, {}] is not a finite interval", general(low), general(high)));
  }
  const double magnitude_of_bounds = std::max(std::abs(low), std::abs(high));
  if (high == low || high - low <= 1e-12 * magnitude_of_bounds) {
    const double half_width = magnitude_of_bounds > 0.0 ? 0.5 * magnitude_of_bounds : 1.0;
    low -= half_width;
    high += half_width;
  }
  const TickStep step = nice_step(high - low, target_count);
  // The tolerance keeps a bound that is a multiple of the step from adding a tick beyond it.
  return ticks_from(std::floor(low / step.value() + 1e-9), std::ceil(high / step.value() - 1e-9),
                    step);
}

LinePlot::LinePlot(std::string title, std::string x_label, std::string y_label, cv::Size size_px)
    : title_(std::move(title)),
      x_label_(std::move(x_label)),
      y_label_(std::move(y_label)),
      size_px_(size_px) {
  require_plot_size(size_px);
}

LinePlot& LinePlot::add_series(std::string name, std::vector<double> x, std::vector<double> y,
                               SeriesStyle style) {
  if (x.size() != y.size()) {
    throw UsageError("plot series '" + name + "': " + std::to_string(x.size()) + " x values but " +
                     std::to_string(y.size()) + " y values");
  }
  series_.push_back({std::move(name), std::move(x), std::move(y), style});
  return *this;
}

LinePlot& LinePlot::show_zero_line(bool shown) {
  zero_line_ = shown;
  return *this;
}

cv::Mat LinePlot::render() const {
  cv::Mat image(size_px_, CV_8UC3, kWhite);
  Bounds bounds;
  for (const Series& s : series_) {
    for (std::size_t i = 0; i < s.x.size(); ++i) bounds.add(s.x[i], s.y[i]);
  }
  if (bounds.empty()) bounds = {0.0, 1.0, 0.0, 1.0};

  Frame frame;
  frame.area = plot_area(size_px_);
  const std::vector<double> x_ticks =
      nice_ticks(bounds.x_low, bounds.x_high, std::max(2, frame.area.width / kPxPerTickX));
  const std::vector<double> y_ticks =
      nice_ticks(bounds.y_low, bounds.y_high, std::max(2, frame.area.height / kPxPerTickY));
  frame.x_low = x_ticks.front();
  frame.x_high = x_ticks.back();
  frame.y_low = y_ticks.front();
  frame.y_high = y_ticks.back();

  draw_axes_background(image, frame, x_ticks, y_ticks);
  if (zero_line_ && frame.y_low <= 0.0 && 0.0 <= frame.y_high) {
    // Axis-parallel lines (grid, zero line) are drawn crisp, on whole pixels.
    const int py = cvRound(frame.to_pixel(0.0, 0.0).y);
    cv::line(image, {frame.area.x, py}, {frame.area.br().x - 1, py}, kZeroLine, 1, cv::LINE_8);
  }

  std::vector<LegendEntry> legend;
  for (std::size_t k = 0; k < series_.size(); ++k) {
    const Series& s = series_[k];
    const cv::Scalar colour = palette_colour(k);
    const bool lines = s.style != SeriesStyle::kPoints;
    const bool markers = s.style != SeriesStyle::kLine;
    bool have_previous = false;
    cv::Point2d previous;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        have_previous = false;  // a gap
        continue;
      }
      const cv::Point2d p = frame.to_pixel(s.x[i], s.y[i]);
      if (lines && have_previous) {
        cv::line(image, subpixel(previous), subpixel(p), colour, 2, cv::LINE_AA, kShift);
      }
      if (markers)
        cv::circle(image, subpixel(p), 3 << kShift, colour, cv::FILLED, cv::LINE_AA, kShift);
      previous = p;
      have_previous = true;
    }
    if (!s.name.empty()) legend.push_back({s.name, colour, lines, markers});
  }

  draw_axes_foreground(image, frame, x_ticks, y_ticks, title_, x_label_, y_label_);
  draw_legend(image, frame, legend);
  return image;
}

void LinePlot::save(const std::filesystem::path& path) const {
  save_png(render(), path);
}

PointsPlot::PointsPlot(std::string title, std::string x_label, std::string y_label,
                       cv::Size size_px)
    : title_(std::move(title)),
      x_label_(std::move(x_label)),
      y_label_(std::move(y_label)),
      size_px_(size_px) {
  require_plot_size(size_px);
}

PointsPlot& PointsPlot::add_points(std::string name, std::vector<cv::Point2d> points,
                                   std::vector<std::string> labels) {
  if (!labels.empty() && labels.size() != points.size()) {
    throw UsageError("point set '" + name + "': " + std::to_string(labels.size()) + " labels for " +
                     std::to_string(points.size()) + " points");
  }
  sets_.push_back({std::move(name), std::move(points), std::move(labels)});
  return *this;
}

PointsPlot& PointsPlot::add_segment(const PlotSegment& segment) {
  if (!(segment.grey >= 0.0 && segment.grey <= 1.0) ||
      !(segment.alpha >= 0.0 && segment.alpha <= 1.0)) {
    throw UsageError("plot segment: grey and alpha must lie in [0, 1] (got " +
                     std::to_string(segment.grey) + ", " + std::to_string(segment.alpha) + ")");
  }
  segments_.push_back(segment);
  return *this;
}

cv::Mat PointsPlot::render() const {
  cv::Mat image(size_px_, CV_8UC3, kWhite);
  Bounds bounds;
  for (const PointSet& set : sets_) {
    for (const cv::Point2d& p : set.points) bounds.add(p.x, p.y);
  }
  for (const PlotSegment& s : segments_) {
    bounds.add(s.from.x, s.from.y);
    bounds.add(s.to.x, s.to.y);
  }
  if (bounds.empty()) bounds = {0.0, 1.0, 0.0, 1.0};
  const Frame frame = equal_scale_frame(bounds, size_px_);

  // One tick step for both axes, so the grid is made of squares.
  const TickStep step =
      nice_step(frame.x_high - frame.x_low, std::max(2, frame.area.width / kPxPerTickX));
  const std::vector<double> x_ticks = ticks_within(frame.x_low, frame.x_high, step);
  const std::vector<double> y_ticks = ticks_within(frame.y_low, frame.y_high, step);

  draw_axes_background(image, frame, x_ticks, y_ticks);

  for (const PlotSegment& s : segments_) {
    if (!std::isfinite(s.from.x) || !std::isfinite(s.from.y) || !std::isfinite(s.to.x) ||
        !std::isfinite(s.to.y)) {
      continue;
    }
    draw_segment(image, frame.to_pixel(s.from.x, s.from.y), frame.to_pixel(s.to.x, s.to.y),
                 255.0 * s.grey, s.alpha);
  }

  std::vector<LegendEntry> legend;
  for (std::size_t k = 0; k < sets_.size(); ++k) {
    const cv::Scalar colour = palette_colour(k);
    for (const cv::Point2d& p : sets_[k].points) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
      cv::circle(image, subpixel(frame.to_pixel(p.x, p.y)), 4 << kShift, colour, cv::FILLED,
                 cv::LINE_AA, kShift);
    }
    if (!sets_[k].name.empty()) legend.push_back({sets_[k].name, colour, false, true});
  }
  // Labels after all points, so that no point hides a label.
  for (const PointSet& set : sets_) {
    for (std::size_t i = 0; i < set.labels.size(); ++i) {
      const cv::Point2d& p = set.points[i];
      if (set.labels[i].empty() || !std::isfinite(p.x) || !std::isfinite(p.y)) continue;
      const cv::Point2d px = frame.to_pixel(p.x, p.y);
      draw_text(image, set.labels[i], {cvRound(px.x) + 6, cvRound(px.y) - 8}, 0.4, Align::kLeft);
    }
  }

  draw_axes_foreground(image, frame, x_ticks, y_ticks, title_, x_label_, y_label_);
  draw_legend(image, frame, legend);
  return image;
}

void PointsPlot::save(const std::filesystem::path& path) const {
  save_png(render(), path);
}

cv::Point2d plot_point(const Eigen::Vector2d& position) {
  return {position.x(), position.y()};
}

std::vector<cv::Point2d> plot_points(const std::vector<Eigen::Vector2d>& positions) {
  std::vector<cv::Point2d> points;
  points.reserve(positions.size());
  for (const Eigen::Vector2d& position : positions) points.push_back(plot_point(position));
  return points;
}

}  // namespace omninav::measures
