#include "omninav/evaluation/compass_evaluation.hpp"

#include <cmath>
#include <sstream>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/measures/robust_regression.hpp"

namespace omninav::evaluation {
namespace {

std::optional<double> robust_slope(const std::vector<double>& x, const std::vector<double>& y) {
  // Theil–Sen needs two distinct x; a camera that never moved has no slope per metre.
  bool distinct = false;
  for (std::size_t i = 1; i < x.size() && !distinct; ++i) distinct = x[i] != x.front();
  if (!distinct) return std::nullopt;
  return measures::theil_sen_fit(x, y).slope;
}

}  // namespace

CompassEvaluation evaluate_compass(const std::vector<compass::CompassEstimate>& estimates,
                                   const std::vector<CompassTruth>& truth, int reference_frames) {
  if (estimates.empty()) throw UsageError("no frames to evaluate");
  if (estimates.size() != truth.size()) {
    throw UsageError(
        "evaluation needs one truth per estimate: " + std::to_string(estimates.size()) +
        " estimates, " + std::to_string(truth.size()) + " truths");
  }
  CompassEvaluation evaluation;
  evaluation.reference_frames = reference_frames;
  evaluation.total_frames = static_cast<int>(estimates.size());
  std::vector<double> estimate_rad, truth_rad, times, timed_errors;
  double travelled = 0.0;
  for (std::size_t i = 0; i < estimates.size(); ++i) {
    estimate_rad.push_back(estimates[i].heading_rad);
    truth_rad.push_back(truth[i].heading_rad);
    if (i > 0) {
      const Eigen::Vector2d step = truth[i].world_position - truth[i - 1].world_position;
      travelled += std::hypot(step.x(), step.y());
    }
    evaluation.distance_m.push_back(travelled);
    const double error_deg = rad_to_deg(signed_difference(estimate_rad.back(), truth_rad.back()));
    evaluation.errors_deg.push_back(error_deg);
    const double sigma_deg = rad_to_deg(estimates[i].heading_sigma_rad);
    evaluation.within_1_sigma += std::abs(error_deg) <= sigma_deg ? 1 : 0;
    evaluation.within_2_sigma += std::abs(error_deg) <= 2.0 * sigma_deg ? 1 : 0;
    if (truth[i].time_s) {
      times.push_back(*truth[i].time_s);
      timed_errors.push_back(error_deg);
    }
  }
  evaluation.error_deg =
      measures::in_degrees(measures::angular_error_stats(estimate_rad, truth_rad));
  evaluation.final_error_deg = evaluation.errors_deg.back();
  if (times.size() == estimates.size()) {
    evaluation.slope_deg_per_s = robust_slope(times, timed_errors);
  }
  // A camera turning on the spot travels nothing (ROTATERIGHT: "n/a" in Table 3); a few
  // micrometres of rounding in the truth file are not travel either.
  if (travelled > 1e-3) {
    evaluation.slope_deg_per_m = robust_slope(evaluation.distance_m, evaluation.errors_deg);
  }
  return evaluation;
}

std::string format_compass_table(const std::string& dataset, const std::string& method,
                                 const CompassEvaluation& evaluation) {
  std::ostringstream table;
  table << "Dataset\tMethod\tNb (total)\tMax. (deg)\tMean (deg)\tStd. dev. (deg)\tSlope (deg/s)"
           "\tSlope (deg/m)\n";
  table << dataset << '\t' << method << '\t' << evaluation.reference_frames << " ("
        << evaluation.total_frames << ")\t" << fixed(evaluation.error_deg.max_abs, 3) << '\t'
        << fixed(evaluation.error_deg.mean, 3) << '\t'
        << (std::isfinite(evaluation.error_deg.stddev) ? fixed(evaluation.error_deg.stddev, 3)
                                                       : std::string("n/a"))
        << '\t' << (evaluation.slope_deg_per_s ? fixed(*evaluation.slope_deg_per_s, 4) : "n/a")
        << '\t' << (evaluation.slope_deg_per_m ? fixed(*evaluation.slope_deg_per_m, 3) : "n/a")
        << '\n';
  table << "Slopes: Theil-Sen robust regression of the error against time and distance "
           "travelled; final error "
        << fixed(evaluation.final_error_deg, 3) << " deg\n";
  return table.str();
}

}  // namespace omninav::evaluation
