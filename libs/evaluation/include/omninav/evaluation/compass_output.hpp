// The results of `omninav compass` (the visual compass, Labrosse 2006) as CSV: one row per
// frame, the statistics of Tables 3-4 as a one-row CSV, and the one-line summary of a run
// without ground truth.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "omninav/compass/compass_run.hpp"
#include "omninav/core/pose.hpp"
#include "omninav/evaluation/compass_evaluation.hpp"

namespace omninav::evaluation {

// One frame of a compass run: the estimate and what the input says of the frame.
struct CompassFrame {
  compass::CompassEstimate estimate;
  std::string source;
  std::optional<double> time_s;
  std::optional<CameraPose> truth;
  // With a map (`omninav compass --map`): the recognised place whose heading re-aligned the
  // compass at this frame (compass::CompassEstimate::realigned), none when it did not.
  std::optional<int> realigned_place;
};

// How rows are written: CSV (a header row, then a line per frame) or JSON lines (an object per
// frame, its keys the CSV's columns, null where the CSV leaves a field empty).
enum class RowFormat { kCsv, kJsonLines };
RowFormat row_format_of(const std::string& name);  // "csv" or "jsonl"; UsageError otherwise

// Writes the frames of a compass run one at a time, each flushed as soon as it is written, so
// that a program reading a live run (`omninav compass --input camera:0 --out -`) sees every
// frame when it is computed. The columns: frame, source, time_s, heading_deg,
// heading_unwrapped_deg, rotation_deg, amplitude_norm, reference_frame, confidence, shift_px,
// evaluations, heading_sigma_deg (the heading's standard deviation,
// compass.yaml's uncertainty); with `with_truth` also truth_heading_deg, error_deg and
// distance_m (travelled over the frames with truth), empty for a frame without truth; with
// `with_map` last realigned_place (CompassFrame::realigned_place, empty when none).
class CompassRowWriter {
 public:
  CompassRowWriter(std::ostream& out, RowFormat format, bool with_truth, bool with_map);
  void write(const CompassFrame& frame);

 private:
  std::ostream& out_;
  RowFormat format_;
  bool with_truth_;
  bool with_map_;
  std::vector<std::string> columns_;
  double travelled_m_ = 0.0;
  std::optional<CameraPose> last_truth_;
};

// Every frame as CSV (CompassRowWriter).
void write_compass_csv(std::ostream& out, const std::vector<CompassFrame>& frames, bool with_truth,
                       bool with_map = false);

// The statistics of Tables 3-4 as a header and one row.
struct CompassStatsRow {
  std::string dataset;
  std::string method;
  int width_px = 0;
};
void write_compass_stats_csv(std::ostream& out, const CompassStatsRow& row,
                             const CompassEvaluation& evaluation);

// Frames, reference frames, the final heading and how many frames were flagged: one line.
void write_compass_summary(std::ostream& out, const std::vector<CompassFrame>& frames,
                           int reference_count, const std::string& method);

}  // namespace omninav::evaluation
