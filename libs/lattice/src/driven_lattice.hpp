#pragma once
// The lattice of a map made by driving: its confirmed links as the measurements of a robust
// pose graph (pose_graph.hpp), solved, and the result in organise's terms.

#include "omninav/lattice/organise.hpp"
#include "omninav/lattice/similar_places.hpp"

namespace omninav::lattice::detail {

// Whether the map has travelled links (consecutive places of a stream) that the robot's
// odometry measured.
bool driven_with_odometry(const memory::VisualMemory& memory);

// The confirmed links between places (headings: lattice_headings, 0 where none) as relative
// poses; revisits switchable. The link's own odometry when both places have it.
std::vector<RelativePoseMeasurement> link_measurements(const memory::VisualMemory& memory,
                                                       const std::vector<MeasuredLink>& links,
                                                       const std::vector<double>& headings_rad,
                                                       double spacing_m,
                                                       const OrganiseParams& params);

// Solves the map's pose graph, with `result`'s springs as weak constraints, into `result`
// (lattice, motions, link counts; the calibration and the springs are already set) and stores
// the positions in `memory`. The revisits are searched among each place's most similar places
// (`most_similar`, as the springs were).
void organise_driven(memory::VisualMemory& memory, const OrganiseParams& params,
                     const PlaceDissimilarities& dissimilarity,
                     const std::vector<std::vector<SimilarPlace>>& most_similar,
                     OrganiseResult& result);

}  // namespace omninav::lattice::detail
