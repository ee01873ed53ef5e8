#pragma once
// 2-D similarity (Procrustes) alignment, for comparing a lattice with the truth
// (docs/design.md, Evaluation: "RMSE of node positions after a similarity alignment to the truth,
// in units of the reference spacing, interior and boundary nodes reported apart"; the lattice
// figures of Menegatti et al. 2004, §3, Figs. 15 and 17).
//
// A lattice relaxed from distances alone is defined up to rotation, translation, scale and
// also reflection, so reflection can be allowed; a lattice constrained by motion directions
// (§3.4) has a handedness, and then a reflection should count as an error.

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

namespace omninav::measures {

// p ↦ linear·p + translation, with linear = scale·R(rotation_rad)·M, where M is the identity,
// or diag(1, −1) (mirror in the x axis, applied first) when `reflected`.
struct Similarity2 {
  Eigen::Matrix2d linear = Eigen::Matrix2d::Identity();
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();
  double scale = 1.0;
  double rotation_rad = 0.0;  // in (−π, π]
  bool reflected = false;

  Eigen::Vector2d apply(const Eigen::Vector2d& point) const { return linear * point + translation; }
};

struct ProcrustesParams {
  bool allow_reflection = false;  // also try mirrored alignments, keep whichever fits better
  bool allow_scale = true;        // false: rigid alignment (scale fixed at 1)
};

struct ProcrustesResult {
  Similarity2 transform;                 // takes `from` onto `onto`
  std::vector<Eigen::Vector2d> aligned;  // transform applied to each point of `from`
  double rmse = 0.0;                     // sqrt(mean |aligned_i − onto_i|²), unit of `onto`
};

// The similarity that minimises Σ |T(from_i) − onto_i|² (least squares, Umeyama 1991), and
// the aligned points. Point i of `from` corresponds to point i of `onto`. Throws UsageError if
// the sizes differ, there are fewer than two points, a coordinate is not finite, or all
// points of `from` coincide (no rotation or scale is defined).
ProcrustesResult align_similarity(std::span<const Eigen::Vector2d> from,
                                  std::span<const Eigen::Vector2d> onto,
                                  const ProcrustesParams& params = {});

// sqrt(mean over i in `subset` of |aligned_i − truth_i|²). NaN for an empty subset (e.g. a
// lattice too small to have interior nodes), so that a report shows "nan" rather than a
// misleading 0. Throws UsageError if the sizes differ or an index is out of range.
double rmse_over(std::span<const Eigen::Vector2d> aligned, std::span<const Eigen::Vector2d> truth,
                 std::span<const std::size_t> subset);

// rmse_over(...) / spacing: the error in units of the reference grid spacing (e.g. the 30 cm
// grid of Menegatti et al. 2004, §3.3), given in the unit of `truth`. Throws UsageError
// unless spacing > 0.
double rmse_in_spacing(std::span<const Eigen::Vector2d> aligned,
                       std::span<const Eigen::Vector2d> truth, std::span<const std::size_t> subset,
                       double spacing);

// RMSE in units of the spacing over all points, and over interior and boundary points apart.
struct SplitRmse {
  double all = 0.0;
  double interior = 0.0;  // NaN when every point is on the boundary
  double boundary = 0.0;  // NaN when no point is on the boundary
  std::size_t interior_count = 0;
  std::size_t boundary_count = 0;
};

// The boundary points are those listed in `boundary_indices` (duplicates ignored); all others
// are interior. The alignment itself is whatever produced `aligned` (normally fitted on all
// points): only the error is split.
SplitRmse split_rmse_in_spacing(std::span<const Eigen::Vector2d> aligned,
                                std::span<const Eigen::Vector2d> truth,
                                std::span<const std::size_t> boundary_indices, double spacing);

}  // namespace omninav::measures
