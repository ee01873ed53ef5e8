// trials.csv and the trials' steps.csv against hand-built outcomes.
#include "omninav/evaluation/trials_output.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "support/csv_text.hpp"

namespace omninav::evaluation {
namespace {

using testing::csv_text_rows;

// Two trials: the first drives two steps (the second one a jump to place 6) and reaches its
// goal, the second matched no goal place and drove nothing.
std::vector<TrialOutcome> two_trials() {
  std::vector<TrialOutcome> outcomes(2);
  TrialOutcome& first = outcomes[0];
  first.trial.start = CameraPose{1.0, 2.0, 1.0, M_PI / 2, 0.0, 0.0};
  first.trial.goal = CameraPose{3.0, 2.0, 1.0, -M_PI / 2, 0.0, 0.0};
  first.goal_place = 6;
  first.stopped_at_goal = first.reached = true;
  first.final_error_m = 0.125;
  first.straight_m = 2.0;
  first.result.path_length_m = 3.0;
  first.result.jumps = 1;
  first.result.homing_steps = 2;
  first.result.lost_events = 2;  // the belief spread twice
  first.result.replans = 3;      // links dropped three times
  first.outside_m = 0.5;
  first.end_outside_m = 0.25;
  first.step_outside_m = {0.5, 0.0};
  navigation::NavigationStep step;
  step.index = 0;
  step.truth = CameraPose{1.0, 2.0, 1.0, M_PI / 2, 0.0, 0.0};
  step.heading_estimate_rad = M_PI / 4;  // lattice frame; the lattice turned by +30°: 75° world
  step.turn_rad = -M_PI / 2;
  first.result.steps.push_back(step);
  step.index = 1;
  step.match = memory::PlaceMatch{};
  step.match->place = 6;
  step.match->similarity = 900.0;
  step.match->dissimilarity_per_value = 1.5;
  step.jump = true;
  first.result.steps.push_back(step);
  outcomes[1].straight_m = 1.0;
  return outcomes;
}

TEST(TrialsOutput, OneRowPerTrial) {
  std::ostringstream csv;
  write_trials_csv(csv, two_trials());
  const auto rows = csv_text_rows(csv.str());
  ASSERT_EQ(rows.size(), 3u);
  ASSERT_EQ(rows[0].size(), 22u);
  EXPECT_EQ(rows[0][13], "path_ratio");
  EXPECT_EQ(std::vector<std::string>(rows[0].begin() + 15, rows[0].end()),
            (std::vector<std::string>{"jumps", "sidesteps", "replans", "homing_steps",
                                      "lost_events", "outside_m", "end_outside_m"}));
  EXPECT_EQ(rows[1], (std::vector<std::string>{"0", "1", "2",     "90", "3",   "2",   "-90", "6",
                                               "1", "1", "0.125", "3",  "2",   "1.5", "2",   "1",
                                               "0", "3", "2",     "2",  "0.5", "0.25"}));
  EXPECT_EQ(rows[2][7], "-1");
  EXPECT_EQ(rows[2][9], "0");
  EXPECT_EQ(rows[2][14], "0");
}

TEST(TrialsOutput, StepsCarryTheTrialAndTheWorldHeadingError) {
  std::ostringstream csv;
  write_trial_steps_csv(csv, two_trials(), 30.0 * M_PI / 180.0);
  const auto rows = csv_text_rows(csv.str());
  ASSERT_EQ(rows.size(), 3u);  // the second trial has no steps
  EXPECT_EQ(rows[0], (std::vector<std::string>{
                         "trial", "step", "x_m", "y_m", "heading_deg", "place", "similarity",
                         "dissimilarity_per_value", "heading_estimate_deg", "heading_error_deg",
                         "turn_deg", "jump", "recognised", "phase", "lost", "outside_m"}));
  // 45° + 30° against a true 90°: -15°; half a metre outside the mapped area.
  EXPECT_EQ(rows[1], (std::vector<std::string>{"0", "0", "1", "2", "90", "-1", "0", "0", "45",
                                               "-15", "-90", "0", "0", "route", "0", "0.5"}));
  EXPECT_EQ(rows[2][5], "6");
  EXPECT_EQ(rows[2][6], "900");
  EXPECT_EQ(rows[2][7], "1.5");
  EXPECT_EQ(rows[2][11], "1");
}

}  // namespace
}  // namespace omninav::evaluation
