#include "headings.hpp"

#include <ceres/ceres.h>

#include <cmath>
#include <set>
#include <utility>

#include "omninav/core/angles.hpp"
#include "omninav/signature/phase_heading.hpp"

namespace omninav::lattice::detail {
namespace {

// A measured turn from one place to another: (θ_to − θ_from − turn), wrapped, in standard
// deviations.
class TurnResidual {
 public:
  TurnResidual(double turn_rad, double stddev_rad)
      : turn_rad_(turn_rad), weight_(1.0 / stddev_rad) {}

  template <typename T>
  bool operator()(const T* const from, const T* const to, T* residual) const {
    const T difference = to[0] - from[0] - T(turn_rad_);
    // Wrapped to [−π, π): as Ceres' examples/slam/pose_graph_2d NormalizeAngle.
    const T two_pi(2.0 * kPi);
    residual[0] = T(weight_) * (difference - two_pi * ceres::floor((difference + T(kPi)) / two_pi));
    return true;
  }

  static ceres::CostFunction* Create(double turn_rad, double stddev_rad) {
    return new ceres::AutoDiffCostFunction<TurnResidual, 1, 1, 1>(
        new TurnResidual(turn_rad, stddev_rad));
  }

 private:
  const double turn_rad_;
  const double weight_;
};

// The compass's turn between consecutive places: good to a degree or two, but for its jumps.
constexpr double kCompassTurnStddevRad = 0.05;  // ~3°
// The phases' turn between a place and one of its most similar places (median 1-3° when near).
constexpr double kPhaseTurnStddevRad = 0.09;  // ~5°

}  // namespace

std::vector<std::optional<double>> synchronise_headings(
    const memory::VisualMemory& memory, std::vector<std::optional<double>> headings,
    const std::vector<std::vector<SimilarPlace>>& ranking, int neighbours) {
  const int count = static_cast<int>(headings.size());
  std::vector<double> theta(count);
  for (int i = 0; i < count; ++i) {
    if (!headings[i]) return headings;
    theta[i] = *headings[i];
  }
  ceres::CauchyLoss loss(1.0);
  ceres::Problem::Options options;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(options);
  std::set<std::pair<int, int>> phased;
  const auto add_phase_turn = [&](int a, int b) {
    if (a == b || !phased.insert({std::min(a, b), std::max(a, b)}).second) return;
    const signature::PhaseHeading turn =
        signature::relative_heading(memory.place(a).signature, memory.place(b).signature);
    problem.AddResidualBlock(TurnResidual::Create(turn.turn_rad, kPhaseTurnStddevRad), &loss,
                             &theta[a], &theta[b]);
  };
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
    const int a = static_cast<int>(edge.from), b = static_cast<int>(edge.to);
    if (edge.edge->kind != memory::EdgeKind::kSequence) continue;
    problem.AddResidualBlock(
        TurnResidual::Create(signed_difference(*headings[b], *headings[a]), kCompassTurnStddevRad),
        &loss, &theta[a], &theta[b]);
    add_phase_turn(a, b);
  }
  for (int a = 0; a < count; ++a) {
    for (const SimilarPlace& similar : most_similar_first(ranking[a], neighbours)) {
      add_phase_turn(a, similar.place);
    }
  }
  if (!problem.HasParameterBlock(&theta[0])) return headings;
  problem.SetParameterBlockConstant(&theta[0]);
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = 100;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  for (int i = 0; i < count; ++i) headings[i] = wrap_angle(theta[i]);
  return headings;
}

}  // namespace omninav::lattice::detail
