#pragma once
// The picture of a lattice (Figs. 14-17 of Menegatti et al. 2004): its springs, and beside
// it, when the map has ground truth, the truth with the lattice aligned over it.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <opencv2/core.hpp>
#include <vector>

#include "omninav/lattice/organise.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav::report {

// The lattice as the truth sees it (evaluation/lattice_score.hpp measures it): its places
// aligned onto their true positions, and the triangles of true neighbours that fold over in it.
struct LatticeOverTruth {
  std::vector<Eigen::Vector2d> aligned;  // place by place, metres in the world's frame
  std::vector<std::array<std::size_t, 3>> folded;
};

// The lattice with its springs shaded by stiffness (dark = stiff) and, beside it when `truth`
// is given, the truth with the aligned lattice over it and the places of folds marked.
cv::Mat lattice_picture(const memory::VisualMemory& memory,
                        const lattice::OrganiseResult& organised,
                        const LatticeOverTruth* truth = nullptr);

}  // namespace omninav::report
