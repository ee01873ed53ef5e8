#include "omninav/evaluation/compass_output.hpp"

#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/core/csv.hpp"
#include "omninav/core/format.hpp"

namespace omninav::evaluation {

void write_compass_csv(std::ostream& out, const std::vector<CompassFrame>& frames, bool with_truth,
                       bool with_map) {
  std::vector<std::string> columns{"frame",
                                   "source",
                                   "time_s",
                                   "heading_deg",
                                   "heading_unwrapped_deg",
                                   "rotation_deg",
                                   "amplitude_norm",
                                   "reference_frame",
                                   "confidence",
                                   "shift_px",
                                   "evaluations",
                                   "pitch_deg",
                                   "roll_deg",
                                   "heading_sigma_deg"};
  if (with_truth) columns.insert(columns.end(), {"truth_heading_deg", "error_deg", "distance_m"});
  if (with_map) columns.push_back("realigned_place");
  write_csv_line(out, columns);
  double travelled = 0.0;
  std::optional<CameraPose> last_truth;
  for (const CompassFrame& row : frames) {
    const compass::CompassEstimate& e = row.estimate;
    std::vector<std::string> fields{
        std::to_string(e.frame_index), row.source, fixed_or_empty(row.time_s, 4),
        // Headings read back exactly (the Python module's test
        // compares them to 1e-9 degrees).
        shortest(rad_to_deg(wrap_angle(e.heading_rad))), shortest(rad_to_deg(e.heading_rad)),
        shortest(rad_to_deg(e.rotation_rad)), fixed(e.amplitude_norm, 4),
        std::to_string(e.reference_index), e.flags.describe(), fixed(e.shift_px, 4),
        std::to_string(e.evaluations), fixed(rad_to_deg(e.pitch_rad), 4),
        fixed(rad_to_deg(e.roll_rad), 4), fixed(rad_to_deg(e.heading_sigma_rad), 4)};
    if (with_truth) {
      if (row.truth) {
        if (last_truth) {
          travelled +=
              std::hypot(row.truth->x_m - last_truth->x_m, row.truth->y_m - last_truth->y_m);
        }
        last_truth = row.truth;
        fields.insert(
            fields.end(),
            {fixed(rad_to_deg(wrap_angle(row.truth->heading_rad)), 4),
             fixed(rad_to_deg(signed_difference(e.heading_rad, row.truth->heading_rad)), 4),
             fixed(travelled, 4)});
      } else {
        fields.resize(fields.size() + 3);
      }
    }
    if (with_map) {
      fields.push_back(row.realigned_place ? std::to_string(*row.realigned_place) : "");
    }
    write_csv_line(out, fields);
  }
}

void write_compass_stats_csv(std::ostream& out, const CompassStatsRow& row,
                             const CompassEvaluation& evaluation) {
  write_csv_line(out, {"dataset", "method", "width_px", "reference_frames", "total_frames",
                       "max_abs_error_deg", "mean_error_deg", "std_error_deg", "slope_deg_per_s",
                       "slope_deg_per_m", "final_error_deg"});
  const double stddev = evaluation.error_deg.stddev;
  write_csv_line(
      out,
      {row.dataset, row.method, std::to_string(row.width_px),
       std::to_string(evaluation.reference_frames), std::to_string(evaluation.total_frames),
       fixed(evaluation.error_deg.max_abs, 4), fixed(evaluation.error_deg.mean, 4),
       std::isfinite(stddev) ? fixed(stddev, 4) : "", fixed_or_empty(evaluation.slope_deg_per_s, 5),
       fixed_or_empty(evaluation.slope_deg_per_m, 4), fixed(evaluation.final_error_deg, 4)});
}

void write_compass_summary(std::ostream& out, const std::vector<CompassFrame>& frames,
                           int reference_count, const std::string& method) {
  const compass::CompassEstimate& last = frames.back().estimate;
  int flagged = 0;
  for (const CompassFrame& frame : frames) flagged += frame.estimate.flags.ok() ? 0 : 1;
  out << frames.size() << " frames, " << reference_count << " reference frames (" << method
      << "); final heading " << fixed(rad_to_deg(wrap_angle(last.heading_rad)), 3) << " deg ("
      << fixed(rad_to_deg(last.heading_rad), 3) << " deg unwrapped); " << flagged
      << " frames with a low-confidence flag\n";
}

}  // namespace omninav::evaluation
