#pragma once
// How good a lattice is, when the map has ground truth (DESIGN.md, Evaluation: Lattice): the
// RMSE of the places after a similarity (Procrustes) alignment to the truth, in units of the
// reference spacing, interior and boundary places apart; whether neighbours fold over; and the
// picture of Figs. 14-17.

#include <array>
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>

#include "omninav/eval/procrustes.hpp"
#include "omninav/lattice/organise.hpp"

namespace omninav::lattice {

struct LatticeEvaluation {
  double spacing_m = 0.0;  // the truth's typical spacing (median nearest-neighbour distance)
  eval::SplitRmse rmse;    // in spacings
  std::vector<std::size_t>
      boundary;  // places with fewer than 8 true neighbours within 1.5 spacings
  std::vector<Eigen::Vector2d> aligned;  // the lattice aligned onto the truth
  // Folds (issue 5: "no neighbours fold over"): the triangles of true neighbours, those of the
  // truth's Delaunay triangulation whose sides are all at most 1.5 spacings, and those of them
  // whose corners go round the other way in the aligned lattice (a place moved across the line
  // through two of its neighbours), or lie on one line.
  int neighbour_triangles = 0;
  std::vector<std::array<std::size_t, 3>> folded;
};

// Nothing when the places lack ground truth or lattice positions. Reflection is allowed in the
// alignment when the lattice had no motion constraints (distances alone cannot tell a lattice
// from its mirror image).
std::optional<LatticeEvaluation> evaluate_against_truth(const memory::VisualMemory& memory,
                                                        bool allow_reflection);

// What `omninav organise` (and `omninav evaluate`) does to a map file: loads it, organises it
// with `params` and scores the lattice against the truth when the places have it (reflection
// allowed when no motion constrained the lattice). It does not write: the caller stores
// `positions` with memory::save_lattice_positions last, after whatever else may fail (the
// picture), so that a failure leaves the map as it was. Throws InputError when a position is
// not finite.
struct OrganisedMap {
  memory::VisualMemory memory;  // with its lattice positions
  OrganiseResult organised;
  std::optional<LatticeEvaluation> evaluation;
  std::vector<memory::LatticePosition> positions;  // place by place, to store in the map
};
OrganisedMap organise_map_file(const std::filesystem::path& map_file, const OrganiseParams& params);

// The lattice with its springs shaded by stiffness (dark = stiff) and, beside it when given,
// the truth with the aligned lattice over it.
cv::Mat lattice_picture(const memory::VisualMemory& memory, const OrganiseResult& organised,
                        const std::optional<LatticeEvaluation>& evaluation);

}  // namespace omninav::lattice
