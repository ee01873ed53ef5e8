#pragma once
// The evaluation of a visual compass run against ground truth, as Tables 3 and 4 of the compass
// paper (Labrosse 2006) and docs/design.md (Evaluation) define it:
//   e = estimate − truth, wrapped to (−180°, 180°] per frame;
//   "Nb (total)": reference frames used, out of all frames;
//   Max. |e|, Mean, Std. dev. over the whole sequence (not only its end, §4.3);
//   Slope (°/s) and (°/m): the slope of a robust linear regression of e against time and
//   against distance travelled. The paper does not name its robust regression; we use Theil–Sen
//   (median of pairwise slopes, omninav::measures::theil_sen_fit, whose header says why).
// The compass is started at the true heading of the first frame (§4.1: "the visual compass is
// initialised with the absolute value at the beginning of the experiment").

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "omninav/compass/visual_compass.hpp"
#include "omninav/measures/error_stats.hpp"

namespace omninav::evaluation {

// Ground truth for one frame of a compass run.
struct CompassTruth {
  double heading_rad = 0.0;
  Eigen::Vector2d world_position = Eigen::Vector2d::Zero();  // metres, on the floor
  std::optional<double> time_s;
};

struct CompassEvaluation {
  int reference_frames = 0;
  int total_frames = 0;
  std::vector<double> errors_deg;         // per frame, wrapped to (−180, 180]
  std::vector<double> distance_m;         // travelled on the floor up to each frame
  measures::ErrorStats error_deg;         // max |e|, mean, std (degrees)
  std::optional<double> slope_deg_per_s;  // absent without times
  std::optional<double> slope_deg_per_m;  // absent when the camera did not travel (on the spot)
  double final_error_deg = 0.0;
  // Frames whose |e| is within 1 and 2 of the compass's heading standard deviations
  // (CompassEstimate::heading_sigma_rad): ~68 % and ~95 % when the uncertainty means something.
  int within_1_sigma = 0;
  int within_2_sigma = 0;
};

// Throws UsageError when the sizes differ or there are no frames.
CompassEvaluation evaluate_compass(const std::vector<compass::CompassEstimate>& estimates,
                                   const std::vector<CompassTruth>& truth, int reference_frames);

// One line per statistic, in the layout of Table 3 (header and a row for `method`).
std::string format_compass_table(const std::string& dataset, const std::string& method,
                                 const CompassEvaluation& evaluation);

}  // namespace omninav::evaluation
