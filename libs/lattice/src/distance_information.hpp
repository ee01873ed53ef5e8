#pragma once
// How much the dissimilarity says about distance on one map, measured from the map alone.
//
// A stream's consecutive places (edges of kind sequence) and a grid database's consecutive
// images (kind listed) come in an order whose gaps are known up to a few exceptions: places i
// and i + k of an unbroken run are k steps apart along the path (on a straight stretch, k steps
// apart; at a raster's row end, anywhere). Fig. 7 says that at short range the dissimilarity
// grows with distance; how well it does on this map is the rank correlation (Spearman's ρ)
// between k and D(i, i + k) over k = 1 .. max_gap. Near 1: the dissimilarity orders distances;
// near 0: it says nothing about them (a natural scene seen from 10 cm, look-alike rooms).

#include <optional>

#include "omninav/lattice/similar_places.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav::lattice::detail {

// Spearman's ρ between the gap k (1..max_gap) of places along unbroken runs of sequence or listed
// edges and their dissimilarity; nothing when fewer than 8 pairs of at least two gaps exist.
std::optional<double> dissimilarity_gap_correlation(const memory::VisualMemory& memory,
                                                    const PlaceDissimilarities& dissimilarity,
                                                    int max_gap);

}  // namespace omninav::lattice::detail
