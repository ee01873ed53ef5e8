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

// One row per frame: frame, source, time_s, heading_deg, heading_unwrapped_deg, rotation_deg,
// amplitude_norm, reference_frame, confidence, shift_px, evaluations, pitch_deg, roll_deg,
// heading_sigma_deg (the heading's standard deviation, compass.yaml's uncertainty); with
// `with_truth` also truth_heading_deg, error_deg and distance_m (travelled over the frames with
// truth), empty for a frame without truth; with `with_map` last realigned_place
// (CompassFrame::realigned_place, empty when none).
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
