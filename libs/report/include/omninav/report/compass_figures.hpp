#pragma once
// Pictures of a visual compass run (libs/compass computes the headings, this draws them).

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "omninav/compass/visual_compass.hpp"

namespace omninav::report {

// Heading (estimate, and truth when given) and error against frame, two panels one above the
// other, as Figs. 8-9 and 16-19 of the compass papers. Unwrapped headings so turns show as
// ramps. `truth_heading_rad` holds one true heading per estimate, or is empty (no truth: the
// heading panel alone). The error panel draws the band of ±1 heading standard deviation; frames
// re-aligned on a map (CompassEstimate::realigned) are points on the estimate.
cv::Mat plot_compass_run(const std::vector<compass::CompassEstimate>& estimates,
                         const std::vector<double>& truth_heading_rad, const std::string& title);

}  // namespace omninav::report
