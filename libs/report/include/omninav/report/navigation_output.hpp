// The steps of a navigation run (`omninav navigate`, the reactive loop of Menegatti et al. 2004,
// §3.5) as CSV.
#pragma once

#include <optional>
#include <ostream>

#include "omninav/navigation/navigator.hpp"

namespace omninav::report {

// The header: step, x_m, y_m, heading_deg (the true pose), place, similarity,
// dissimilarity_per_value (the match; place -1 when none), heading_estimate_deg,
// heading_error_deg, turn_deg, jump; after a first column `trial` when `with_trial`.
void write_navigation_steps_header(std::ostream& out, bool with_trial);

// One row per step, after the trial's index when given. The lattice frame turns with the first
// place's heading (lattice::lattice_headings): a heading in it plus `lattice_to_world_rad` is a
// heading in the world, when the map stores one.
void write_navigation_steps(std::ostream& out, const navigation::NavigationResult& result,
                            double lattice_to_world_rad,
                            std::optional<std::size_t> trial = std::nullopt);

}  // namespace omninav::report
