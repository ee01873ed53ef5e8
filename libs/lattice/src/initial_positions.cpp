#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>

#include "omninav/core/errors.hpp"
#include "omninav/lattice/spring_lattice.hpp"

namespace omninav::lattice {
namespace {

// Dead reckoning: walk the motion chain from place 0, each step as long as the spring between
// its ends (the median spring length when there is none). Empty when a place is not reached.
std::vector<Eigen::Vector2d> dead_reckoning(int place_count,
                                            const std::vector<SpringMeasurement>& springs,
                                            const std::vector<MotionMeasurement>& motions) {
  std::map<std::pair<int, int>, double> length_of;
  std::vector<double> lengths;
  for (const SpringMeasurement& spring : springs) {
    length_of[{std::min(spring.a, spring.b), std::max(spring.a, spring.b)}] = spring.length_m;
    lengths.push_back(spring.length_m);
  }
  double median_length = 1.0;
  if (!lengths.empty()) {
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    median_length = lengths[lengths.size() / 2];
  }
  std::vector<Eigen::Vector2d> positions(place_count, Eigen::Vector2d::Zero());
  std::vector<bool> placed(place_count, false);
  placed[0] = true;
  // Motions may come in any order: sweep until nothing new is placed.
  for (bool progress = true; progress;) {
    progress = false;
    for (const MotionMeasurement& motion : motions) {
      if (!placed[motion.from] || placed[motion.to]) continue;
      const auto found =
          length_of.find({std::min(motion.from, motion.to), std::max(motion.from, motion.to)});
      const double step = found != length_of.end() ? found->second : median_length;
      positions[motion.to] =
          positions[motion.from] +
          step * Eigen::Vector2d(std::cos(motion.direction_rad), std::sin(motion.direction_rad));
      placed[motion.to] = progress = true;
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
  std::vector<std::vector<std::pair<int, double>>> neighbours(place_count);
  for (const SpringMeasurement& spring : springs) {
    neighbours[spring.a].emplace_back(spring.b, spring.length_m);
    neighbours[spring.b].emplace_back(spring.a, spring.length_m);
  }
  const double infinity = std::numeric_limits<double>::infinity();
  Eigen::MatrixXd squared(place_count, place_count);
  for (int source = 0; source < place_count; ++source) {  // Dijkstra from every place
    std::vector<double> distance(place_count, infinity);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    distance[source] = 0.0;
    queue.emplace(0.0, source);
    while (!queue.empty()) {
      const auto [d, place] = queue.top();
      queue.pop();
      if (d > distance[place]) continue;
      for (const auto& [next, length] : neighbours[place]) {
        if (d + length < distance[next]) {
          distance[next] = d + length;
          queue.emplace(distance[next], next);
        }
      }
    }
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
  std::vector<Eigen::Vector2d> positions = dead_reckoning(place_count, springs, motions);
  return positions.empty() ? classical_mds(place_count, springs) : positions;
}

}  // namespace omninav::lattice
