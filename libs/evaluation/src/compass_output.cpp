#include "omninav/evaluation/compass_output.hpp"

#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/core/csv.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/json.hpp"

namespace omninav::evaluation {

namespace {

// The columns whose values are words, not numbers (JSON strings).
bool is_text_column(const std::string& column) {
  return column == "source" || column == "confidence";
}

}  // namespace

RowFormat row_format_of(const std::string& name) {
  if (name == "csv") return RowFormat::kCsv;
  if (name == "jsonl") return RowFormat::kJsonLines;
  throw UsageError("--format " + name + ": expected csv or jsonl");
}

CompassRowWriter::CompassRowWriter(std::ostream& out, RowFormat format, bool with_truth,
                                   bool with_map)
    : out_(out), format_(format), with_truth_(with_truth), with_map_(with_map) {
  columns_ = {
      "frame",        "source",           "time_s",          "heading_deg", "heading_unwrapped_deg",
      "rotation_deg", "amplitude_norm",   "reference_frame", "confidence",  "shift_px",
      "evaluations",  "heading_sigma_deg"};
  if (with_truth_)
    columns_.insert(columns_.end(), {"truth_heading_deg", "error_deg", "distance_m"});
  if (with_map_) columns_.push_back("realigned_place");
  if (format_ == RowFormat::kCsv) {
    write_csv_line(out_, columns_);
    out_.flush();
  }
}

void CompassRowWriter::write(const CompassFrame& row) {
  const compass::CompassEstimate& e = row.estimate;
  std::vector<std::string> fields{
      std::to_string(e.frame_index), row.source, fixed_or_empty(row.time_s, 4),
      // Headings read back exactly (the Python module's test compares them to 1e-9 degrees).
      shortest(rad_to_deg(wrap_angle(e.heading_rad))), shortest(rad_to_deg(e.heading_rad)),
      shortest(rad_to_deg(e.rotation_rad)), fixed(e.amplitude_norm, 4),
      std::to_string(e.reference_index), e.flags.describe(), fixed(e.shift_px, 4),
      std::to_string(e.evaluations), fixed(rad_to_deg(e.heading_sigma_rad), 4)};
  if (with_truth_) {
    if (row.truth) {
      if (last_truth_) {
        travelled_m_ +=
            std::hypot(row.truth->x_m - last_truth_->x_m, row.truth->y_m - last_truth_->y_m);
      }
      last_truth_ = row.truth;
      fields.insert(fields.end(),
                    {fixed(rad_to_deg(wrap_angle(row.truth->heading_rad)), 4),
                     fixed(rad_to_deg(signed_difference(e.heading_rad, row.truth->heading_rad)), 4),
                     fixed(travelled_m_, 4)});
    } else {
      fields.resize(fields.size() + 3);
    }
  }
  if (with_map_) {
    fields.push_back(row.realigned_place ? std::to_string(*row.realigned_place) : "");
  }
  if (format_ == RowFormat::kCsv) {
    write_csv_line(out_, fields);
  } else {
    // The same text as the CSV's fields, so that both formats carry the same digits.
    Json object;
    for (std::size_t i = 0; i < columns_.size(); ++i) {
      const std::string& field = fields[i];
      if (field.empty()) {
        object[columns_[i]] = nullptr;
      } else if (is_text_column(columns_[i])) {
        object[columns_[i]] = field;
      } else {
        object[columns_[i]] = Json::parse(field);
      }
    }
    out_ << object.dump(-1, ' ', false, Json::error_handler_t::replace) << '\n';
  }
  out_.flush();
}

void write_compass_csv(std::ostream& out, const std::vector<CompassFrame>& frames, bool with_truth,
                       bool with_map) {
  CompassRowWriter writer(out, RowFormat::kCsv, with_truth, with_map);
  for (const CompassFrame& frame : frames) writer.write(frame);
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
