#pragma once
// The organised visual memory as the planner and the navigator see it.

#include <memory>
#include <vector>

#include "omninav/memory/localisation.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/navigation/navigator.hpp"
#include "omninav/navigation/route_planner.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::navigation {

// Every place's lattice position and its heading in the lattice frame. Throws UsageError when
// the map has no lattice yet ("run omninav organise") or a place has no heading (neither
// stored nor measurable along the exploration).
std::vector<PlaceNode> places_from_memory(const memory::VisualMemory& memory);

// The median distance from each place to its nearest neighbour on the lattice.
double lattice_spacing(const std::vector<PlaceNode>& places);

// A navigator's localiser backed by the memory's hierarchical localisation: the best place,
// its similarity, and the robot's heading relative to the place from the phases. The
// localiser and the extractor must outlive the returned function.
Localiser memory_localiser(const memory::Localiser& localiser,
                           signature::SignatureExtractor& extractor);

}  // namespace omninav::navigation
