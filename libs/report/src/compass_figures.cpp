#include "omninav/report/compass_figures.hpp"

#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/measures/plot.hpp"

namespace omninav::report {
namespace {

// The unwrapped sequence of angles (radians), so that turns show as ramps.
std::vector<double> unwrapped_deg(const std::vector<double>& angles_rad) {
  std::vector<double> result;
  result.reserve(angles_rad.size());
  double previous = 0.0;
  double accumulated = 0.0;
  for (std::size_t i = 0; i < angles_rad.size(); ++i) {
    accumulated = i == 0 ? angles_rad[i] : accumulated + signed_difference(angles_rad[i], previous);
    previous = angles_rad[i];
    result.push_back(rad_to_deg(accumulated));
  }
  return result;
}

}  // namespace

cv::Mat plot_compass_run(const std::vector<compass::CompassEstimate>& estimates,
                         const std::vector<double>& truth_heading_rad, const std::string& title) {
  std::vector<double> frames, heading_rad;
  for (const compass::CompassEstimate& estimate : estimates) {
    frames.push_back(estimate.frame_index);
    heading_rad.push_back(estimate.heading_rad);
  }
  const bool with_truth =
      !truth_heading_rad.empty() && truth_heading_rad.size() == estimates.size();
  measures::LinePlot headings(title + ": heading", "frame", "heading (deg, unwrapped)",
                              cv::Size(900, 420));
  // The estimate is already unwrapped (Algorithm 1 accumulates); the truth is unwrapped here,
  // then moved by whole turns to start where the estimate starts.
  std::vector<double> estimate_deg;
  for (const double h : heading_rad) estimate_deg.push_back(rad_to_deg(h));
  headings.add_series("visual compass", frames, estimate_deg);
  if (with_truth) {
    std::vector<double> truth_deg = unwrapped_deg(truth_heading_rad);
    const double turns = std::round((estimate_deg.front() - truth_deg.front()) / 360.0);
    for (double& value : truth_deg) value += 360.0 * turns;
    headings.add_series("ground truth", frames, truth_deg);
  }
  // The frames re-aligned on a map's place (`omninav compass --map`), as points on the estimate.
  std::vector<double> realigned_frames, realigned_deg;
  for (std::size_t i = 0; i < estimates.size(); ++i) {
    if (!estimates[i].realigned) continue;
    realigned_frames.push_back(frames[i]);
    realigned_deg.push_back(estimate_deg[i]);
  }
  if (!realigned_frames.empty()) {
    headings.add_series("re-aligned on the map", std::move(realigned_frames),
                        std::move(realigned_deg), measures::SeriesStyle::kPoints);
  }
  cv::Mat picture = headings.render();
  if (with_truth) {
    std::vector<double> errors;
    for (std::size_t i = 0; i < estimates.size(); ++i) {
      errors.push_back(rad_to_deg(signed_difference(heading_rad[i], truth_heading_rad[i])));
    }
    measures::LinePlot error(title + ": error (estimate - truth)", "frame", "error (deg)",
                             cv::Size(900, 320));
    error.add_series("error", frames, errors).show_zero_line();
    // The band of ±1 standard deviation (CompassEstimate::heading_sigma_rad).
    std::vector<double> upper, lower;
    for (const compass::CompassEstimate& estimate : estimates) {
      upper.push_back(rad_to_deg(estimate.heading_sigma_rad));
      lower.push_back(-upper.back());
    }
    error.add_series("+1 sigma", frames, upper);
    error.add_series("-1 sigma", frames, std::move(lower));
    cv::vconcat(picture, error.render(), picture);
  }
  return picture;
}

}  // namespace omninav::report
