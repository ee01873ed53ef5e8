#pragma once
// How good a lattice is, when the map has ground truth (docs/design.md, Evaluation: Lattice): the
// RMSE of the places after a similarity (Procrustes) alignment to the truth, in units of the
// reference spacing, interior and boundary places apart; and whether neighbours fold over.

#include <cstddef>
#include <optional>
#include <vector>

#include "omninav/measures/procrustes.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/report/lattice_figures.hpp"

namespace omninav::evaluation {

// The aligned lattice and its folds (report::LatticeOverTruth, which the lattice's picture
// draws), and the numbers they give.
//   aligned: the lattice aligned onto the truth;
//   folded: of the triangles of true neighbours (those of the truth's Delaunay triangulation
//   whose sides are all at most 1.5 spacings), those whose corners go round the other way in
//   the aligned lattice (a place moved across the line through two of its neighbours), or lie
//   on one line.
struct LatticeScore : report::LatticeOverTruth {
  double spacing_m = 0.0;    // the truth's typical spacing (median nearest-neighbour distance)
  measures::SplitRmse rmse;  // in spacings
  std::vector<std::size_t> boundary;  // places with fewer than 8 true neighbours within 1.5
                                      // spacings
  int neighbour_triangles = 0;        // the triangles of true neighbours
};

// Nothing when the places lack ground truth or lattice positions. Reflection is allowed in the
// alignment when the lattice had no motion constraints (distances alone cannot tell a lattice
// from its mirror image).
std::optional<LatticeScore> score_lattice(const memory::VisualMemory& memory,
                                          bool allow_reflection);

}  // namespace omninav::evaluation
