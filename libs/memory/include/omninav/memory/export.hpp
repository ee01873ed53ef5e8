#pragma once
// Exporting a map for other tools (docs/design.md, Data formats: Maps): places and edges as CSV
// (one header row, units in the column names, degrees at the edges), or the whole graph as
// GraphML written by Boost.Graph's write_graphml. Missing values are empty CSV fields and NaN
// in GraphML.

#include <ostream>

#include "omninav/memory/visual_memory.hpp"

namespace omninav::memory {

// place_id, run_id, source, frame_index, time_s, heading_deg, heading_source, truth_x_m,
// truth_y_m, truth_z_m, truth_heading_deg, lattice_x, lattice_y
void write_places_csv(const VisualMemory& memory, std::ostream& out);

// edge_id, from_place, to_place, kind, dissimilarity, relative_heading_deg, heading_confidence,
// motion_bearing_deg, motion_bearing_stddev_deg, parallax_deg
void write_edges_csv(const VisualMemory& memory, std::ostream& out);

// Nodes carry the place columns above (numbers as double, NaN when missing), edges the edge
// columns.
void write_graphml(const VisualMemory& memory, std::ostream& out);

}  // namespace omninav::memory
