#include <ceres/ceres.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <cmath>
#include <limits>
#include <queue>

#include "motion_blocks.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/lattice/spring_lattice.hpp"
#include "place_sets.hpp"

namespace omninav::lattice {
namespace {

// Dead reckoning: a breadth-first walk from place 0 along the motions (either way round),
// each place placed by the first motion that reaches it. Empty when a place is not reached.
std::vector<Eigen::Vector2d> dead_reckoning(int place_count,
                                            const std::vector<MotionMeasurement>& motions) {
  std::vector<std::vector<std::pair<int, Eigen::Vector2d>>> steps(place_count);
  for (const MotionMeasurement& motion : motions) {
    const Eigen::Vector2d step = motion.length_m * Eigen::Vector2d(std::cos(motion.direction_rad),
                                                                   std::sin(motion.direction_rad));
    steps[motion.from].emplace_back(motion.to, step);
    steps[motion.to].emplace_back(motion.from, -step);
  }
  std::vector<Eigen::Vector2d> positions(place_count, Eigen::Vector2d::Zero());
  std::vector<bool> placed(place_count, false);
  std::queue<int> queue;
  placed[0] = true;
  queue.push(0);
  while (!queue.empty()) {
    const int place = queue.front();
    queue.pop();
    for (const auto& [next, step] : steps[place]) {
      if (placed[next]) continue;
      positions[next] = positions[place] + step;
      placed[next] = true;
      queue.push(next);
    }
  }
  if (std::find(placed.begin(), placed.end(), false) != placed.end()) return {};
  return positions;
}

// Classical MDS (Torgerson): the top two eigenvectors of the double-centred squared distances,
// distances being shortest paths through the springs (Isomap), so that missing pairs are filled.
std::vector<Eigen::Vector2d> classical_mds(int place_count,
                                           const std::vector<SpringMeasurement>& springs) {
  constexpr int kMaxPlaces = 4000;  // an n×n dense matrix; beyond this, motions are needed
  if (place_count > kMaxPlaces) {
    throw UsageError(
        "lattice: " + std::to_string(place_count) +
        " places without a motion chain: too many for a multidimensional-scaling start (at most " +
        std::to_string(kMaxPlaces) + ")");
  }
  // Boost.Graph's Dijkstra from every place over the springs.
  using Graph =
      boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                            boost::property<boost::edge_weight_t, double>>;
  Graph graph(place_count);
  for (const SpringMeasurement& spring : springs)
    boost::add_edge(spring.a, spring.b, spring.length_m, graph);
  const double infinity = std::numeric_limits<double>::infinity();
  Eigen::MatrixXd squared(place_count, place_count);
  std::vector<double> distance(place_count);
  for (int source = 0; source < place_count; ++source) {
    boost::dijkstra_shortest_paths(
        graph, source,
        boost::distance_map(distance.data()).distance_inf(infinity).distance_zero(0.0));
    for (int target = 0; target < place_count; ++target) {
      if (distance[target] == infinity) {
        throw UsageError("lattice: place " + std::to_string(target) +
                         " is not connected to place " + std::to_string(source) + " by any spring");
      }
      squared(source, target) = distance[target] * distance[target];
    }
  }
  const Eigen::MatrixXd centring =
      Eigen::MatrixXd::Identity(place_count, place_count) -
      Eigen::MatrixXd::Constant(place_count, place_count, 1.0 / place_count);
  const Eigen::MatrixXd gram = -0.5 * centring * squared * centring;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram);
  // Eigenvalues come in increasing order: the last two span the best plane.
  std::vector<Eigen::Vector2d> positions(place_count);
  for (int i = 0; i < place_count; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const int column = place_count - 1 - axis;
      positions[i][axis] =
          eigen.eigenvectors()(i, column) * std::sqrt(std::max(0.0, eigen.eigenvalues()(column)));
    }
  }
  const Eigen::Vector2d origin = positions[0];
  for (Eigen::Vector2d& position : positions) position -= origin;
  return positions;
}

}  // namespace

std::vector<Eigen::Vector2d> initial_positions(int place_count,
                                               const std::vector<SpringMeasurement>& springs,
                                               const std::vector<MotionMeasurement>& motions) {
  if (place_count == 1) return {Eigen::Vector2d::Zero()};
  // The steps, and the other motions across the stretches the steps join.
  detail::PlaceSets stretches(place_count);
  for (const MotionMeasurement& motion : motions) {
    if (motion.step) stretches.join(motion.from, motion.to);
  }
  std::vector<MotionMeasurement> start;
  for (const MotionMeasurement& motion : motions) {
    if (motion.step || !stretches.joined(motion.from, motion.to)) start.push_back(motion);
  }
  std::vector<Eigen::Vector2d> positions = dead_reckoning(place_count, start);
  if (positions.empty()) return classical_mds(place_count, springs);
  // Dead reckoning follows one tree of motions and carries each one's error to every place
  // beyond it. The motions together, without a robust loss, are a linear least-squares problem
  // (MotionResidual is linear in the positions): its one minimum averages the errors out.
  ceres::Problem problem;
  detail::add_motion_blocks(problem, start, positions, nullptr);
  problem.SetParameterBlockConstant(positions[0].data());
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return positions;
}

}  // namespace omninav::lattice
