// The picture of a compass run (compass_figures.hpp).
#include "omninav/report/compass_figures.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "omninav/core/angles.hpp"

namespace omninav::report {
namespace {

std::vector<compass::CompassEstimate> turning_estimates(int frames) {
  std::vector<compass::CompassEstimate> estimates;
  for (int i = 0; i < frames; ++i) {
    compass::CompassEstimate estimate;
    estimate.frame_index = i;
    estimate.heading_rad = deg_to_rad(170.0 + 20.0 * i);  // unwrapped, past 180° and round
    estimates.push_back(estimate);
  }
  return estimates;
}

// The heading panel (900 x 420), and below it the error panel (900 x 320) when every frame has
// its truth; a truth of another length is no truth.
TEST(CompassFigures, ErrorPanelOnlyWithATruthPerFrame) {
  const std::vector<compass::CompassEstimate> estimates = turning_estimates(40);
  std::vector<double> truth;
  for (const compass::CompassEstimate& e : estimates) truth.push_back(wrap_angle(e.heading_rad));
  const cv::Mat with_truth = plot_compass_run(estimates, truth, "test");
  EXPECT_EQ(with_truth.size(), cv::Size(900, 420 + 320));
  EXPECT_EQ(plot_compass_run(estimates, {}, "test").size(), cv::Size(900, 420));
  truth.pop_back();
  EXPECT_EQ(plot_compass_run(estimates, truth, "test").size(), cv::Size(900, 420));
}

// Frames re-aligned on a map are drawn on the heading panel; without any, nothing is added.
TEST(CompassFigures, ReAlignedFramesAreMarked) {
  std::vector<compass::CompassEstimate> estimates = turning_estimates(40);
  const cv::Mat plain = plot_compass_run(estimates, {}, "test");
  estimates[10].realigned = true;
  estimates[30].realigned = true;
  const cv::Mat marked = plot_compass_run(estimates, {}, "test");
  ASSERT_EQ(marked.size(), plain.size());
  cv::Mat difference;
  cv::absdiff(marked, plain, difference);
  EXPECT_GT(cv::countNonZero(difference.reshape(1)), 0);
}

}  // namespace
}  // namespace omninav::report
