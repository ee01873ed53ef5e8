#include "omninav/report/navigation_output.hpp"

#include <string>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/csv.hpp"
#include "omninav/core/format.hpp"

namespace omninav::report {

void write_navigation_steps_header(std::ostream& out, bool with_trial, bool with_outside) {
  out << (with_trial ? "trial," : "")
      << "step,x_m,y_m,heading_deg,place,similarity,dissimilarity_per_value,heading_estimate_deg,"
         "heading_error_deg,turn_deg,jump,recognised,phase,lost"
      << (with_outside ? ",outside_m" : "") << "\n";
}

void write_navigation_steps(std::ostream& out, const navigation::NavigationResult& result,
                            double lattice_to_world_rad, std::optional<std::size_t> trial,
                            const std::vector<double>& outside_m) {
  for (std::size_t i = 0; i < result.steps.size(); ++i) {
    const navigation::NavigationStep& step = result.steps[i];
    std::vector<std::string> row;
    if (trial) row.push_back(std::to_string(*trial));
    row.insert(
        row.end(),
        {std::to_string(step.index), general(step.truth.x_m), general(step.truth.y_m),
         general(rad_to_deg(step.truth.heading_rad)),
         step.match ? std::to_string(step.match->place) : "-1",
         general(step.match ? step.match->similarity : 0.0),
         general(step.match ? step.match->dissimilarity_per_value : 0.0),
         general(rad_to_deg(step.heading_estimate_rad)),
         general(rad_to_deg(signed_difference(step.heading_estimate_rad + lattice_to_world_rad,
                                              step.truth.heading_rad))),
         general(rad_to_deg(step.turn_rad)), step.jump ? "1" : "0", step.recognised ? "1" : "0",
         navigation::phase_name(step.phase), step.lost ? "1" : "0"});
    if (!outside_m.empty()) row.push_back(general(outside_m.at(i)));
    write_csv_line(out, row);
  }
}

}  // namespace omninav::report
