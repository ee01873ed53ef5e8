#pragma once
// Small PNG plots drawn with OpenCV: error curves (LinePlot) and 2-D point sets with edges, such
// as a lattice over the true grid (PointsPlot). Our dependency stack (docs/design.md, Debian
// packages) has no plotting library, and evaluation pictures only need lines, points, ticks
// and text, so they are drawn here with cv::line / cv::putText (cv::FONT_HERSHEY_SIMPLEX,
// anti-aliased with cv::LINE_AA). Images are BGR, CV_8UC3.

#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace omninav::measures {

// Colour i of the fixed palette (Tableau 10, BGR), cycling after 10. The k-th series or point
// set added to a plot gets palette_colour(k).
cv::Scalar palette_colour(std::size_t index);

// Ticks for an axis covering [low, high]: consecutive multiples of a "nice" step (1, 2 or 5
// times a power of ten) giving about `target_count` intervals, the first ≤ low and the last
// ≥ high. A degenerate range (low == high) is widened around its value first. Throws
// UsageError if a bound is not finite or low > high.
std::vector<double> nice_ticks(double low, double high, int target_count = 6);

enum class SeriesStyle { kLine, kPoints, kLineAndPoints };

// Curves y(x) with automatic axis ranges (the nice ticks around all finite data), grid, tick
// labels, axis labels, a title and a legend (top right) of the named series.
class LinePlot {
 public:
  LinePlot(std::string title, std::string x_label, std::string y_label,
           cv::Size size_px = cv::Size(900, 500));

  // Adds a series in the next palette colour. Points that are not finite are skipped and break
  // the line. An empty name leaves the series out of the legend. Throws UsageError if x and y
  // differ in size.
  LinePlot& add_series(std::string name, std::vector<double> x, std::vector<double> y,
                       SeriesStyle style = SeriesStyle::kLine);

  // A horizontal line at y = 0 (dark grey, drawn when 0 lies within the y range), e.g. under
  // an error curve.
  LinePlot& show_zero_line(bool shown = true);

  cv::Mat render() const;
  // render() written as PNG by save_png: InputError naming the file if it cannot be written.
  void save(const std::filesystem::path& path) const;

 private:
  struct Series {
    std::string name;
    std::vector<double> x, y;
    SeriesStyle style;
  };
  std::string title_, x_label_, y_label_;
  cv::Size size_px_;
  std::vector<Series> series_;
  bool zero_line_ = false;
};

// Positions (Eigen, the libraries' type) as the plots' points.
cv::Point2d plot_point(const Eigen::Vector2d& position);
std::vector<cv::Point2d> plot_points(const std::vector<Eigen::Vector2d>& positions);

// A segment under the points: grey level 0 (black) to 1 (white), alpha 0 (invisible) to 1
// (opaque), e.g. a spring drawn darker the stiffer it is.
struct PlotSegment {
  cv::Point2d from;
  cv::Point2d to;
  double grey = 0.6;
  double alpha = 1.0;
};

// Point sets and segments in the plane with equal scales on both axes (a metre is as long
// across as up), so shapes are not distorted.
class PointsPlot {
 public:
  explicit PointsPlot(std::string title, std::string x_label = "x", std::string y_label = "y",
                      cv::Size size_px = cv::Size(900, 500));

  // Adds a point set in the next palette colour; `labels` is empty or holds one label per
  // point, drawn beside it. Throws UsageError if the label count is wrong.
  PointsPlot& add_points(std::string name, std::vector<cv::Point2d> points,
                         std::vector<std::string> labels = {});

  // Segments are drawn below all points, in the order added. Throws UsageError if grey or
  // alpha is outside [0, 1].
  PointsPlot& add_segment(const PlotSegment& segment);

  cv::Mat render() const;
  void save(const std::filesystem::path& path) const;

 private:
  struct PointSet {
    std::string name;
    std::vector<cv::Point2d> points;
    std::vector<std::string> labels;
  };
  std::string title_, x_label_, y_label_;
  cv::Size size_px_;
  std::vector<PointSet> sets_;
  std::vector<PlotSegment> segments_;
};

}  // namespace omninav::measures
