#include "omninav/evaluation/trials_output.hpp"

#include "omninav/core/angles.hpp"
#include "omninav/core/csv.hpp"
#include "omninav/core/format.hpp"
#include "omninav/report/navigation_output.hpp"

namespace omninav::evaluation {

void write_trials_csv(std::ostream& out, const std::vector<TrialOutcome>& outcomes) {
  out << "trial,start_x_m,start_y_m,start_heading_deg,goal_x_m,goal_y_m,goal_heading_deg,"
         "goal_place,stopped_at_goal,reached,final_error_m,path_m,straight_m,path_ratio,steps,"
         "jumps,sidesteps,replans,homing_steps,lost_events,outside_m,end_outside_m\n";
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const TrialOutcome& o = outcomes[i];
    const navigation::NavigationResult& r = o.result;
    write_csv_line(out, {std::to_string(i),
                         general(o.trial.start.x_m),
                         general(o.trial.start.y_m),
                         general(rad_to_deg(o.trial.start.heading_rad)),
                         general(o.trial.goal.x_m),
                         general(o.trial.goal.y_m),
                         general(rad_to_deg(o.trial.goal.heading_rad)),
                         std::to_string(o.goal_place),
                         o.stopped_at_goal ? "1" : "0",
                         o.reached ? "1" : "0",
                         general(o.final_error_m),
                         general(r.path_length_m),
                         general(o.straight_m),
                         general(r.path_length_m / o.straight_m),
                         std::to_string(r.steps.size()),
                         std::to_string(r.jumps),
                         std::to_string(r.sidesteps),
                         std::to_string(r.replans),
                         std::to_string(r.homing_steps),
                         std::to_string(r.lost_events),
                         general(o.outside_m),
                         general(o.end_outside_m)});
  }
}

void write_trial_steps_csv(std::ostream& out, const std::vector<TrialOutcome>& outcomes,
                           double lattice_to_world_rad) {
  report::write_navigation_steps_header(out, true, true);
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const TrialOutcome& o = outcomes[i];
    // Outcomes made by run_trials alone do not know the mapped area: 0 outside.
    const std::vector<double> outside_m = o.step_outside_m.size() == o.result.steps.size()
                                              ? o.step_outside_m
                                              : std::vector<double>(o.result.steps.size(), 0.0);
    report::write_navigation_steps(out, o.result, lattice_to_world_rad, i, outside_m);
  }
}

}  // namespace omninav::evaluation
