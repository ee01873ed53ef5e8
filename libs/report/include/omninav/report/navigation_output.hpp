// The steps of a navigation run (`omninav navigate`, the reactive loop of Menegatti et al. 2004,
// §3.5) as CSV.
#pragma once

#include <optional>
#include <ostream>
#include <vector>

#include "omninav/navigation/navigator.hpp"

namespace omninav::report {

// The header: step, x_m, y_m, heading_deg (the true pose), place (the place the robot acted
// on), similarity (its probability in the belief × 1000), dissimilarity_per_value (of the view
// to it), heading_estimate_deg, heading_error_deg, turn_deg, jump, recognised (the belief
// confident), phase (route, homing: navigation::phase_name), lost (the belief spread); after a
// first column `trial` when `with_trial`, and with a last column outside_m (how far the robot
// stood outside the mapped area, from the evaluation's truth) when `with_outside`.
void write_navigation_steps_header(std::ostream& out, bool with_trial, bool with_outside = false);

// One row per step, after the trial's index when given. The lattice frame turns with the first
// place's heading (lattice::lattice_headings): a heading in it plus `lattice_to_world_rad` is a
// heading in the world, when the map stores one. `outside_m`, when not empty, holds the
// outside_m column, one value per step.
void write_navigation_steps(std::ostream& out, const navigation::NavigationResult& result,
                            double lattice_to_world_rad,
                            std::optional<std::size_t> trial = std::nullopt,
                            const std::vector<double>& outside_m = {});

}  // namespace omninav::report
