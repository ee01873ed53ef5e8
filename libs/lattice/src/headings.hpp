#pragma once
// The places' headings for the motions, made consistent across the map: a stream's headings from
// the visual compass are good from one place to the next but jump where the robot turned on
// the spot (the compass loses part of the turn between two frames), and the jumps add up: on
// the zig-zags of the full suite their median error is 15-100° by the end. The turn between two
// places that are truly near is measured well by the phases themselves (Eq. 1,
// relative_heading: median 1-3°, 90th percentile 3-14° on those maps), and each place's most
// similar places are mostly near, across the rows of a zig-zag as much as along them. So the
// compass is kept along each straight stretch of the stream (steps that turn at most
// `straight_turn_rad`), and one correction per stretch is solved from the phases' turns between
// places of different stretches and the compass's turns across the bends, each with a Cauchy
// loss (a look-alike's turn, or a bend where the compass jumped, is an outlier); the first
// place's stretch is held. A correction per place (every place free) moves single places where
// the compass was right (docs/lattice.md).

#include <optional>
#include <vector>

#include "omninav/lattice/similar_places.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav::lattice::detail {

// `headings` in the lattice frame (lattice_headings), every place with one; `ranking` each
// place's most similar places, of which the first `neighbours` are used. Returns the headings
// unchanged when a place has none.
std::vector<std::optional<double>> synchronise_headings(
    const memory::VisualMemory& memory, std::vector<std::optional<double>> headings,
    const std::vector<std::vector<SimilarPlace>>& ranking, int neighbours,
    double straight_turn_rad);

// The median of angles: the median of their differences from their circular mean, about it.
double circular_median(const std::vector<double>& angles_rad);

}  // namespace omninav::lattice::detail
