#include "omninav/measures/plot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "measures/scratch_dir.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::measures {
namespace {

using testing::ScratchDir;

// A pixel "is" a colour when every channel is within 40 levels: the core of an anti-aliased
// line of width 2 is the colour itself, its fringe is blended with the white background.
bool near_colour(const cv::Vec3b& pixel, const cv::Scalar& colour, int tolerance) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(pixel[k] - static_cast<int>(colour[k])) > tolerance) return false;
  }
  return true;
}

// The rows in which more than `min_share` of the pixels have the colour.
std::vector<int> rows_mostly(const cv::Mat& image, const cv::Scalar& colour, double min_share,
                             int tolerance = 40) {
  std::vector<int> rows;
  for (int r = 0; r < image.rows; ++r) {
    int count = 0;
    for (int c = 0; c < image.cols; ++c)
      count += near_colour(image.at<cv::Vec3b>(r, c), colour, tolerance);
    if (count > min_share * image.cols) rows.push_back(r);
  }
  return rows;
}

cv::Rect bounding_box_of(const cv::Mat& image, const cv::Scalar& colour) {
  cv::Mat mask(image.size(), CV_8U, cv::Scalar(0));
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      if (near_colour(image.at<cv::Vec3b>(r, c), colour, 10)) mask.at<uchar>(r, c) = 255;
    }
  }
  return cv::boundingRect(mask);
}

TEST(NiceTicks, CoverTheRangeWithNiceSteps) {
  EXPECT_EQ(nice_ticks(0.0, 10.0, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  for (auto [low, high] : std::vector<std::pair<double, double>>{
           {0.6, 1.7}, {-3.2, 0.01}, {1e-4, 3e-4}, {-250.0, 12000.0}, {0.0, 0.6}}) {
    const std::vector<double> ticks = nice_ticks(low, high, 6);
    ASSERT_GE(ticks.size(), 2u);
    const double step = ticks[1] - ticks[0];
    // Bounds that are multiples of the step are ticks themselves (to rounding).
    EXPECT_LE(ticks.front(), low + 1e-9 * step);
    EXPECT_GE(ticks.back(), high - 1e-9 * step);
    // Not more than one step of slack at either end, and about 6 intervals.
    EXPECT_GT(ticks.front() + step, low);
    EXPECT_LT(ticks.back() - step, high);
    EXPECT_GE(ticks.size(), 4u);
    EXPECT_LE(ticks.size(), 13u);
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
                std::abs(mantissa - 5) < 1e-9)
        << "step " << step;
  }
  // A single value is widened around itself.
  const std::vector<double> around_one = nice_ticks(1.0, 1.0);
  EXPECT_LT(around_one.front(), 1.0);
  EXPECT_GT(around_one.back(), 1.0);
  EXPECT_THROW(nice_ticks(2.0, 1.0), UsageError);
  EXPECT_THROW(nice_ticks(0.0, INFINITY), UsageError);
  // The message gives DBL_MAX in a dozen characters, not 309 digits.
  try {
    nice_ticks(1.7976931348623157e308, 0.0);
    ADD_FAILURE() << "a reversed range was accepted";
  } catch (const UsageError& error) {
    EXPECT_LT(std::string(error.what()).size(), 100u) << error.what();
  }
}

TEST(LinePlot, WritesAPngOfTheRequestedSize) {
  ScratchDir dir("line_plot_size");
  LinePlot plot("Compass error", "time (s)", "error (deg)", cv::Size(640, 360));
  plot.add_series("error", {0, 1, 2, 3}, {0.5, -0.2, 0.1, 0.3});
  plot.save(dir / "plot.png");
  const cv::Mat read = cv::imread((dir / "plot.png").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(read.empty());
  EXPECT_EQ(read.cols, 640);
  EXPECT_EQ(read.rows, 360);
  const cv::Mat defaults = LinePlot("t", "x", "y").render();
  EXPECT_EQ(defaults.cols, 900);
  EXPECT_EQ(defaults.rows, 500);
  EXPECT_EQ(defaults.type(), CV_8UC3);
}

TEST(LinePlot, HorizontalLineIsOneRowOfTheSeriesColour) {
  ScratchDir dir("line_plot_row");
  std::vector<double> x, y;
  for (int i = 0; i <= 10; ++i) {
    x.push_back(i);
    y.push_back(1.0);
  }
  LinePlot plot("y = 1", "x", "y");
  plot.add_series("one", x, y);
  plot.save(dir / "line.png");
  const cv::Mat image = cv::imread((dir / "line.png").string(), cv::IMREAD_COLOR);
  ASSERT_EQ(image.size(), cv::Size(900, 500));

  // The line spans x ∈ [0, 10], the whole x range, so most of the width of the plot area
  // (which is most of the image) is series-coloured on the line's row: 1 to 3 adjacent rows
  // (width 2, anti-aliased), inside the image away from the title and the x labels.
  const std::vector<int> rows = rows_mostly(image, palette_colour(0), 0.6);
  ASSERT_FALSE(rows.empty()) << "no row of the series colour";
  EXPECT_LE(rows.size(), 3u);
  EXPECT_EQ(rows.back() - rows.front(), static_cast<int>(rows.size()) - 1);
  EXPECT_GT(rows.front(), 50);
  EXPECT_LT(rows.back(), 450);
  // No other series colour there, and nothing of this colour elsewhere but the legend.
  EXPECT_TRUE(rows_mostly(image, palette_colour(1), 0.05).empty());
}

TEST(LinePlot, HigherValuesAreHigherInTheImage) {
  std::vector<double> x = {0, 5, 10};
  const cv::Mat image = LinePlot("two lines", "x", "y")
                            .add_series("zero", x, {0, 0, 0})
                            .add_series("one", x, {1, 1, 1})
                            .render();
  const std::vector<int> zero_rows = rows_mostly(image, palette_colour(0), 0.6);
  const std::vector<int> one_rows = rows_mostly(image, palette_colour(1), 0.6);
  ASSERT_FALSE(zero_rows.empty());
  ASSERT_FALSE(one_rows.empty());
  EXPECT_LT(one_rows.back(), zero_rows.front());
  // Ticks are nice values covering [0, 1] (0, 0.2, ... 1): the two lines are the bottom and
  // top of the y range, so they lie about a plot-area height apart (500 − margins ≈ 390).
  EXPECT_GT(zero_rows.front() - one_rows.back(), 300);
}

TEST(LinePlot, GapsAndZeroLine) {
  // A NaN breaks the line; the zero line is drawn crisp and dark grey (90) across the plot
  // area: exactly that grey, which no frame (60) or grid (228) pixel has.
  const cv::Mat image =
      LinePlot("gap", "x", "y")
          .add_series("", {0, 1, 2, 3, 4}, {-1, 1, NAN, 1, -1}, SeriesStyle::kLineAndPoints)
          .show_zero_line()
          .render();
  EXPECT_FALSE(rows_mostly(image, cv::Scalar(90, 90, 90), 0.6, 0).empty());
  const cv::Mat without =
      LinePlot("gap", "x", "y").add_series("", {0, 1, 2, 3, 4}, {-1, 1, NAN, 1, -1}).render();
  EXPECT_TRUE(rows_mostly(without, cv::Scalar(90, 90, 90), 0.6, 0).empty());
}

TEST(LinePlot, UnwritablePathIsAnInputErrorNamingTheFile) {
  ScratchDir dir("line_plot_unwritable");
  { std::ofstream(dir / "not_a_folder") << "x"; }
  const std::filesystem::path bad = dir / "not_a_folder" / "plot.png";
  LinePlot plot("t", "x", "y");
  plot.add_series("s", {0, 1}, {0, 1});
  try {
    plot.save(bad);
    FAIL() << "no error for " << bad;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
  EXPECT_THROW(plot.add_series("bad", {0, 1}, {0}), UsageError);
  EXPECT_THROW(LinePlot("t", "x", "y", cv::Size(10, 10)), UsageError);
}

TEST(PointsPlot, EqualAspectRatio) {
  // A unit square's corners on a 900×500 canvas: as many pixels across as up.
  const cv::Mat image =
      PointsPlot("square").add_points("", {{0, 0}, {1, 0}, {0, 1}, {1, 1}}).render();
  ASSERT_EQ(image.size(), cv::Size(900, 500));
  const cv::Rect box = bounding_box_of(image, palette_colour(0));
  ASSERT_GT(box.width, 100);
  EXPECT_NEAR(box.width, box.height, 2);
}

TEST(PointsPlot, SegmentsAreDrawnWithTheirGreyAndAlpha) {
  // Corners of the unit square fix the mapping: their dots (radius 4) bound the square ±4 px.
  PointsPlot plot("segments");
  // No name, so no legend swatch of the same colour.
  plot.add_points("", {{0, 0}, {1, 0}, {0, 1}, {1, 1}}, {"a", "b", "c", "d"});
  plot.add_segment({{0.0, 0.25}, {1.0, 0.25}, 0.0, 1.0});  // black, opaque
  plot.add_segment({{0.0, 0.75}, {1.0, 0.75}, 0.0, 0.5});  // black, half transparent
  const cv::Mat image = plot.render();
  const cv::Rect box = bounding_box_of(image, palette_colour(0));
  const double side = box.width - 9.0;
  auto row_of = [&](double y) { return box.y + 4.0 + (1.0 - y) * side; };
  const int column = cvRound(box.x + 4.0 + 0.6 * side);
  auto darkest_near = [&](double y) {
    int darkest = 255;
    for (int r = cvRound(row_of(y)) - 2; r <= cvRound(row_of(y)) + 2; ++r) {
      const cv::Vec3b p = image.at<cv::Vec3b>(r, column);
      darkest = std::min(darkest, static_cast<int>(p[1]));
    }
    return darkest;
  };
  EXPECT_LT(darkest_near(0.25), 40);  // opaque black
  // Half of black over white is 128; over a light grid line (228) 114; anti-aliasing only
  // lightens it.
  EXPECT_GT(darkest_near(0.75), 100);
  EXPECT_LT(darkest_near(0.75), 160);
  // And nothing dark where no segment is.
  EXPECT_GT(darkest_near(0.5), 200);
}

TEST(PointsPlot, RejectsBadArguments) {
  PointsPlot plot("bad");
  EXPECT_THROW(plot.add_points("p", {{0, 0}, {1, 1}}, {"only one"}), UsageError);
  EXPECT_THROW(plot.add_segment({{0, 0}, {1, 1}, 1.5, 1.0}), UsageError);
  EXPECT_THROW(plot.add_segment({{0, 0}, {1, 1}, 0.5, -0.1}), UsageError);
  ScratchDir dir("points_plot_unwritable");
  EXPECT_THROW(plot.save(dir / "missing_folder" / "p.png"), InputError);
}

}  // namespace
}  // namespace omninav::measures
