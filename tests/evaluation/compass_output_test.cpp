// The compass's per-frame CSV, its statistics row and its summary against hand-built frames.
#include "omninav/evaluation/compass_output.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "support/csv_text.hpp"

namespace omninav::evaluation {
namespace {

using testing::csv_text_rows;

// Three frames: the camera starts at (0, 0) heading 90°, drives 3 m then 4 m; the compass reads
// 400° (unwrapped) at the second, the third has no truth.
std::vector<CompassFrame> three_frames() {
  std::vector<CompassFrame> frames(3);
  const char* const sources[] = {"f0.png", "f1.png", "f2.png"};
  for (int i = 0; i < 3; ++i) {
    frames[i].estimate.frame_index = i;
    frames[i].source = sources[i];
  }
  frames[0].estimate.heading_rad = M_PI / 2;
  frames[0].truth = CameraPose{0.0, 0.0, 1.0, M_PI / 2, 0.0, 0.0};
  frames[0].time_s = 0.5;
  frames[1].estimate.heading_rad = 400.0 * M_PI / 180.0;
  frames[1].estimate.rotation_rad = -M_PI / 4;
  frames[1].estimate.amplitude_norm = 0.75;
  frames[1].estimate.reference_index = 0;
  frames[1].estimate.shift_px = -2.5;
  frames[1].estimate.evaluations = 17;
  frames[1].estimate.flags.featureless = true;
  frames[1].estimate.heading_sigma_rad = 1.5 * M_PI / 180.0;
  frames[1].truth = CameraPose{3.0, 0.0, 1.0, 30.0 * M_PI / 180.0, 0.0, 0.0};
  frames[2].truth = std::nullopt;
  return frames;
}

TEST(CompassOutput, CsvRowsCarryTheEstimateAndTheErrorAgainstTruth) {
  std::ostringstream csv;
  write_compass_csv(csv, three_frames(), true);
  const auto rows = csv_text_rows(csv.str());
  ASSERT_EQ(rows.size(), 4u);
  ASSERT_EQ(rows[0].size(), 15u);
  EXPECT_EQ(rows[0][3], "heading_deg");
  EXPECT_EQ(rows[0][11], "heading_sigma_deg");
  EXPECT_EQ(rows[0][14], "distance_m");
  EXPECT_EQ(rows[1][2], "0.5000");
  EXPECT_EQ(std::stod(rows[1][3]), 90.0);
  EXPECT_EQ(rows[1][14], "0.0000");
  // 400° wraps to 40°; the truth is 30°: 10° of error; 3 m travelled. The headings and the
  // rotation are printed to read back exactly (through radians: 40° is 40.00000000000001).
  std::vector<std::string> second = rows[2];
  EXPECT_NEAR(std::stod(second[3]), 40.0, 1e-12);
  EXPECT_NEAR(std::stod(second[4]), 400.0, 1e-12);
  EXPECT_NEAR(std::stod(second[5]), -45.0, 1e-12);
  second[3] = second[4] = second[5] = "";
  const std::vector<std::string> rest{
      "1",           "f1.png",  "",   "",       "",        "",        "0.7500", "0",
      "featureless", "-2.5000", "17", "1.5000", "30.0000", "10.0000", "3.0000"};
  EXPECT_EQ(second, rest);
  // No truth: the truth columns are empty.
  EXPECT_EQ(rows[3][12], "");
  EXPECT_EQ(rows[3][14], "");

  std::ostringstream without;
  write_compass_csv(without, three_frames(), false);
  EXPECT_EQ(csv_text_rows(without.str())[0].size(), 12u);
}

TEST(CompassOutput, StatsRowHasTheTablesColumns) {
  CompassEvaluation evaluation;
  evaluation.reference_frames = 4;
  evaluation.total_frames = 20;
  evaluation.error_deg.max_abs = 3.5;
  evaluation.error_deg.mean = -1.25;
  evaluation.error_deg.stddev = std::nan("");
  evaluation.slope_deg_per_m = 0.125;
  evaluation.final_error_deg = 2.0;
  std::ostringstream csv;
  write_compass_stats_csv(csv, {"rotate", "Atm 0.6055", 360}, evaluation);
  const auto rows = csv_text_rows(csv.str());
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0][5], "max_abs_error_deg");
  EXPECT_EQ(rows[1], (std::vector<std::string>{"rotate", "Atm 0.6055", "360", "4", "20", "3.5000",
                                               "-1.2500", "", "", "0.1250", "2.0000"}));
}

TEST(CompassOutput, SummaryCountsFramesAndFlags) {
  std::ostringstream text;
  write_compass_summary(text, three_frames(), 2, "Fx 0");
  EXPECT_EQ(text.str(),
            "3 frames, 2 reference frames (Fx 0); final heading 0.000 deg (0.000 deg unwrapped); "
            "1 frames with a low-confidence flag\n");
}

}  // namespace
}  // namespace omninav::evaluation
