#include "omninav/measures/procrustes.hpp"

// GCC 12 at -O2 reports -Wstringop-overread inside Eigen::umeyama (Umeyama.h:157, the 2-vector
// translation stored into the 3×3 result by a 16-byte SSE packet on a path the runtime size
// never takes): a known class of GCC 12 false positives, silenced for this header only.
#pragma GCC diagnostic push
#if !defined(__clang__)  // clang has no such warning, and warns about the unknown name
#pragma GCC diagnostic ignored "-Wstringop-overread"
#endif
#include <Eigen/Geometry>
#pragma GCC diagnostic pop
#include <cmath>
#include <limits>
#include <string>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::measures {
namespace {

Eigen::Matrix2Xd as_matrix(std::span<const Eigen::Vector2d> points) {
  Eigen::Matrix2Xd matrix(2, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    matrix.col(static_cast<Eigen::Index>(i)) = points[i];
  }
  return matrix;
}

double rmse_of(const Eigen::Matrix2Xd& aligned, const Eigen::Matrix2Xd& onto) {
  return std::sqrt((aligned - onto).colwise().squaredNorm().mean());
}

void require_same_size(std::size_t a, std::size_t b, const char* what) {
  if (a != b) {
    throw UsageError(std::string(what) + ": " + std::to_string(a) + " points but " +
                     std::to_string(b) + " to compare them with");
  }
}

}  // namespace

ProcrustesResult align_similarity(std::span<const Eigen::Vector2d> from,
                                  std::span<const Eigen::Vector2d> onto,
                                  const ProcrustesParams& params) {
  require_same_size(from.size(), onto.size(), "Procrustes alignment");
  if (from.size() < 2) throw UsageError("Procrustes alignment: needs at least two points");
  const Eigen::Matrix2Xd source = as_matrix(from);
  const Eigen::Matrix2Xd target = as_matrix(onto);
  if (!source.allFinite() || !target.allFinite()) {
    throw UsageError("Procrustes alignment: a coordinate is not finite");
  }
  const Eigen::Vector2d centroid = source.rowwise().mean();
  if ((source.colwise() - centroid).squaredNorm() == 0.0) {
    throw UsageError("Procrustes alignment: all points to align coincide");
  }

  // Eigen::umeyama solves exactly this least-squares problem, but always returns a proper
  // rotation (Umeyama's correction S = diag(1, −1) when det(U)·det(V) < 0). Every 2-D
  // orthogonal map with det −1 is R·M with M = diag(1, −1), so the best alignment with
  // reflection allowed is the better of umeyama(from) and umeyama(M·from).
  const Eigen::Matrix2d mirror = Eigen::Vector2d(1.0, -1.0).asDiagonal();
  auto solve = [&](bool reflect) {
    const Eigen::Matrix2d pre = reflect ? mirror : Eigen::Matrix2d::Identity();
    const Eigen::Matrix3d h = Eigen::umeyama(pre * source, target, params.allow_scale);
    Similarity2 t;
    t.linear = h.topLeftCorner<2, 2>() * pre;
    t.translation = h.topRightCorner<2, 1>();
    const Eigen::Matrix2d scaled_rotation = h.topLeftCorner<2, 2>();
    t.scale = std::sqrt(std::abs(scaled_rotation.determinant()));
    t.rotation_rad = wrap_angle(std::atan2(scaled_rotation(1, 0), scaled_rotation(0, 0)));
    t.reflected = reflect;
    return t;
  };
  auto aligned_by = [&](const Similarity2& t) -> Eigen::Matrix2Xd {
    return (t.linear * source).colwise() + t.translation;
  };

  Similarity2 best = solve(false);
  Eigen::Matrix2Xd best_aligned = aligned_by(best);
  double best_rmse = rmse_of(best_aligned, target);
  if (params.allow_reflection) {
    const Similarity2 mirrored = solve(true);
    Eigen::Matrix2Xd mirrored_aligned = aligned_by(mirrored);
    const double mirrored_rmse = rmse_of(mirrored_aligned, target);
    if (mirrored_rmse < best_rmse) {  // a tie keeps the unreflected alignment
      best = mirrored;
      best_aligned = std::move(mirrored_aligned);
      best_rmse = mirrored_rmse;
    }
  }

  ProcrustesResult result;
  result.transform = best;
  result.rmse = best_rmse;
  result.aligned.reserve(from.size());
  for (Eigen::Index i = 0; i < best_aligned.cols(); ++i)
    result.aligned.emplace_back(best_aligned.col(i));
  return result;
}

double rmse_over(std::span<const Eigen::Vector2d> aligned, std::span<const Eigen::Vector2d> truth,
                 std::span<const std::size_t> subset) {
  require_same_size(aligned.size(), truth.size(), "RMSE");
  if (subset.empty()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  for (std::size_t i : subset) {
    if (i >= aligned.size()) {
      throw UsageError("RMSE: index " + std::to_string(i) + " is out of range (" +
                       std::to_string(aligned.size()) + " points)");
    }
    sum += (aligned[i] - truth[i]).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(subset.size()));
}

double rmse_in_spacing(std::span<const Eigen::Vector2d> aligned,
                       std::span<const Eigen::Vector2d> truth, std::span<const std::size_t> subset,
                       double spacing) {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) {
    throw UsageError("RMSE in spacing: the spacing must be positive (got " +
                     std::to_string(spacing) + ")");
  }
  return rmse_over(aligned, truth, subset) / spacing;
}

SplitRmse split_rmse_in_spacing(std::span<const Eigen::Vector2d> aligned,
                                std::span<const Eigen::Vector2d> truth,
                                std::span<const std::size_t> boundary_indices, double spacing) {
  require_same_size(aligned.size(), truth.size(), "RMSE");
  std::vector<bool> on_boundary(aligned.size(), false);
  for (std::size_t i : boundary_indices) {
    if (i >= aligned.size()) {
      throw UsageError("RMSE: boundary index " + std::to_string(i) + " is out of range (" +
                       std::to_string(aligned.size()) + " points)");
    }
    on_boundary[i] = true;
  }
  std::vector<std::size_t> all, interior, boundary;
  for (std::size_t i = 0; i < aligned.size(); ++i) {
    all.push_back(i);
    (on_boundary[i] ? boundary : interior).push_back(i);
  }
  SplitRmse split;
  split.all = rmse_in_spacing(aligned, truth, all, spacing);
  split.interior = rmse_in_spacing(aligned, truth, interior, spacing);
  split.boundary = rmse_in_spacing(aligned, truth, boundary, spacing);
  split.interior_count = interior.size();
  split.boundary_count = boundary.size();
  return split;
}

}  // namespace omninav::measures
