// The navigation trials of `omninav navigate --trials` as CSV: one row per trial, and every step
// of every trial.
#pragma once

#include <ostream>
#include <vector>

#include "omninav/evaluation/navigation_trials.hpp"

namespace omninav::evaluation {

// trials.csv: trial, start_x_m, start_y_m, start_heading_deg, goal_x_m, goal_y_m,
// goal_heading_deg, goal_place, stopped_at_goal, reached, final_error_m, path_m, straight_m,
// path_ratio, steps, jumps, sidesteps, replans, homing_steps, lost_events (times the belief
// spread), outside_m (the farthest the robot stood outside the mapped area) and end_outside_m
// (where it stopped); navigation::NavigationResult.
void write_trials_csv(std::ostream& out, const std::vector<TrialOutcome>& outcomes);

// steps.csv of the trials: report::write_navigation_steps's columns after the trial's index,
// with outside_m (0 for outcomes whose step_outside_m is not set).
void write_trial_steps_csv(std::ostream& out, const std::vector<TrialOutcome>& outcomes,
                           double lattice_to_world_rad);

}  // namespace omninav::evaluation
