#include "headings.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "omninav/core/angles.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/core/turn_residual.hpp"
#include "omninav/signature/phase_heading.hpp"

namespace omninav::lattice::detail {
namespace {

// A measured turn as a Ceres cost (core/turn_residual.hpp).
ceres::CostFunction* turn_cost(double turn_rad, double stddev_rad) {
  return new ceres::AutoDiffCostFunction<TurnResidual, 1, 1, 1>(
      new TurnResidual(turn_rad, stddev_rad));
}

// The compass's turn across a bend (where it may have jumped): kept unless the phases say
// otherwise.
constexpr double kCompassTurnStddevRad = 0.05;  // ~3°
// The phases' turn between a place and one of its most similar places (median 1-3° when near).
constexpr double kPhaseTurnStddevRad = 0.09;  // ~5°

// The stretches of the stream between bends: consecutive places joined by a step whose turn
// (by the compass) is at most `straight_turn_rad`. Each place's stretch index.
std::vector<int> straight_stretches(const memory::VisualMemory& memory,
                                    const std::vector<std::optional<double>>& headings,
                                    double straight_turn_rad) {
  const int count = static_cast<int>(headings.size());
  std::vector<int> parent(count);
  for (int i = 0; i < count; ++i) parent[i] = i;
  const auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
    const int a = static_cast<int>(edge.from), b = static_cast<int>(edge.to);
    if (edge.edge->kind == memory::EdgeKind::kSequence &&
        std::abs(signed_difference(*headings[b], *headings[a])) <= straight_turn_rad) {
      parent[root(a)] = root(b);
    }
  }
  std::vector<int> stretch(count, -1), index_of_root(count, -1);
  int stretches = 0;
  for (int i = 0; i < count; ++i) {
    int& index = index_of_root[root(i)];
    if (index < 0) index = stretches++;
    stretch[i] = index;
  }
  return stretch;
}

}  // namespace

double circular_median(const std::vector<double>& angles_rad) {
  double sine = 0.0, cosine = 0.0;
  for (const double angle : angles_rad) {
    sine += std::sin(angle);
    cosine += std::cos(angle);
  }
  const double mean = std::atan2(sine, cosine);
  std::vector<double> around;
  for (const double angle : angles_rad) around.push_back(signed_difference(angle, mean));
  return wrap_angle(mean + median(std::move(around)));
}

std::vector<std::optional<double>> synchronise_headings(
    const memory::VisualMemory& memory, std::vector<std::optional<double>> headings,
    const std::vector<std::vector<SimilarPlace>>& ranking, int neighbours,
    double straight_turn_rad) {
  const int count = static_cast<int>(headings.size());
  for (int i = 0; i < count; ++i) {
    if (!headings[i]) return headings;
  }
  const std::vector<int> stretch = straight_stretches(memory, headings, straight_turn_rad);
  // One correction per stretch: the compass is kept along each straight stretch.
  std::vector<double> correction(*std::max_element(stretch.begin(), stretch.end()) + 1, 0.0);
  ceres::CauchyLoss loss(1.0);
  ceres::Problem::Options options;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(options);
  const auto add = [&](int a, int b, double turn_rad, double stddev_rad) {
    if (stretch[a] == stretch[b]) return;
    // θ = compass + correction: the measured turn less the compass's is the corrections'.
    const double corrections_turn = signed_difference(turn_rad, *headings[b] - *headings[a]);
    problem.AddResidualBlock(turn_cost(corrections_turn, stddev_rad), &loss,
                             &correction[stretch[a]], &correction[stretch[b]]);
  };
  std::set<std::pair<int, int>> phased;
  const auto add_phase_turn = [&](int a, int b) {
    if (a == b || stretch[a] == stretch[b] ||
        !phased.insert({std::min(a, b), std::max(a, b)}).second) {
      return;
    }
    const signature::PhaseHeading turn =
        signature::relative_heading(memory.place(a).signature, memory.place(b).signature);
    add(a, b, turn.turn_rad, kPhaseTurnStddevRad);
  };
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
    const int a = static_cast<int>(edge.from), b = static_cast<int>(edge.to);
    if (edge.edge->kind != memory::EdgeKind::kSequence) continue;
    add(a, b, signed_difference(*headings[b], *headings[a]), kCompassTurnStddevRad);
    add_phase_turn(a, b);
  }
  for (int a = 0; a < count; ++a) {
    for (const SimilarPlace& similar : most_similar_first(ranking[a], neighbours)) {
      add_phase_turn(a, similar.place);
    }
  }
  if (!problem.HasParameterBlock(&correction[stretch[0]])) return headings;
  problem.SetParameterBlockConstant(&correction[stretch[0]]);
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  if (correction.size() > 200) solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = 100;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  for (int i = 0; i < count; ++i) headings[i] = wrap_angle(*headings[i] + correction[stretch[i]]);
  return headings;
}

}  // namespace omninav::lattice::detail
