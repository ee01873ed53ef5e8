#include "omninav/lattice/pose_graph.hpp"

#include <ceres/ceres.h>

#include <boost/pending/disjoint_sets.hpp>
#include <cmath>
#include <deque>
#include <memory>

#include "omninav/core/errors.hpp"
#include "omninav/core/param_check.hpp"
#include "omninav/core/turn_residual.hpp"
#include "omninav/lattice/residuals.hpp"

namespace omninav::lattice {

void PoseGraphParams::check() const {
  check_range("pose_graph.switch_prior_stddev", switch_prior_stddev, 0.01, 100.0);
  check_range("pose_graph.max_iterations", max_iterations, 1, 100000);
  check_range("pose_graph.threads", threads, 1, 1024);
}

namespace {

// One measurement's residual: the pose of `to` seen from `from` against the measured one, in
// standard deviations, the translation's along and across its measured direction. A
// switchable measurement's residual is scaled by its switch.
class RelativePoseCost {
 public:
  explicit RelativePoseCost(const RelativePoseMeasurement& measurement)
      : measurement_(measurement) {
    const double length = measurement.translation_m.norm();
    along_ = length > 0.0 ? Eigen::Vector2d(measurement.translation_m / length)
                          : Eigen::Vector2d::UnitX();
  }

  template <typename T>
  bool residual(const T* from, const T* to, T* residuals) const {
    const T dx = to[0] - from[0], dy = to[1] - from[1];
    const T c = ceres::cos(from[2]), s = ceres::sin(from[2]);
    const T error_x = c * dx + s * dy - T(measurement_.translation_m.x());
    const T error_y = -s * dx + c * dy - T(measurement_.translation_m.y());
    residuals[0] =
        (T(along_.x()) * error_x + T(along_.y()) * error_y) / T(measurement_.along_stddev_m);
    residuals[1] =
        (T(-along_.y()) * error_x + T(along_.x()) * error_y) / T(measurement_.across_stddev_m);
    residuals[2] =
        wrapped_angle(to[2] - from[2] - T(measurement_.turn_rad)) / T(measurement_.turn_stddev_rad);
    return true;
  }

 private:
  RelativePoseMeasurement measurement_;
  Eigen::Vector2d along_;
};

struct FixedCost : RelativePoseCost {
  using RelativePoseCost::RelativePoseCost;
  template <typename T>
  bool operator()(const T* from, const T* to, T* residuals) const {
    return residual(from, to, residuals);
  }
};

struct SwitchedCost : RelativePoseCost {
  using RelativePoseCost::RelativePoseCost;
  template <typename T>
  bool operator()(const T* from, const T* to, const T* on, T* residuals) const {
    residual(from, to, residuals);
    for (int i = 0; i < 3; ++i) residuals[i] *= on[0];
    return true;
  }
};

// The switch's prior: on (1) unless the graph pays more to keep it.
struct SwitchPrior {
  double stddev;
  template <typename T>
  bool operator()(const T* on, T* residual) const {
    residual[0] = (T(1.0) - on[0]) / T(stddev);
    return true;
  }
};

// A spring between two poses' positions.
struct PoseSpring {
  SpringResidual spring;
  template <typename T>
  bool operator()(const T* a, const T* b, T* r) const {
    return spring(a, b, r);
  }
};

// `pose` composed with a measurement from it.
Eigen::Vector3d compose(const Eigen::Vector3d& pose, const Eigen::Vector2d& translation,
                        double turn) {
  const double c = std::cos(pose.z()), s = std::sin(pose.z());
  return {pose.x() + c * translation.x() - s * translation.y(),
          pose.y() + s * translation.x() + c * translation.y(), wrapped_angle(pose.z() + turn)};
}

// `pose` un-composed: the pose `from` of which `to` is the measurement's result.
Eigen::Vector3d decompose(const Eigen::Vector3d& to, const Eigen::Vector2d& translation,
                          double turn) {
  const double heading = wrapped_angle(to.z() - turn);
  const double c = std::cos(heading), s = std::sin(heading);
  return {to.x() - (c * translation.x() - s * translation.y()),
          to.y() - (s * translation.x() + c * translation.y()), heading};
}

// `pose` moved rigidly so that `from` lands on `to`.
Eigen::Vector3d moved(const Eigen::Vector3d& pose, const Eigen::Vector3d& from,
                      const Eigen::Vector3d& to) {
  const double turn = wrapped_angle(to.z() - from.z());
  const double c = std::cos(turn), s = std::sin(turn);
  const Eigen::Vector2d offset = pose.head<2>() - from.head<2>();
  return {to.x() + c * offset.x() - s * offset.y(), to.y() + s * offset.x() + c * offset.y(),
          wrapped_angle(pose.z() + turn)};
}

// Starting poses, and each place's piece (by its first place): dead reckoning along the
// robot's own path (the unswitchable measurements) from the first place of each stretch, which
// starts at the origin facing +x; then each revisit that joins two pieces moves the later piece
// rigidly onto the earlier one. A wrong revisit thus moves a piece but cannot bend one.
std::vector<int> dead_reckoning(int count, const std::vector<RelativePoseMeasurement>& measured,
                                std::vector<Eigen::Vector3d>& poses) {
  std::vector<std::vector<int>> at(count);
  for (std::size_t m = 0; m < measured.size(); ++m) {
    if (measured[m].switchable) continue;
    at[measured[m].from].push_back(static_cast<int>(m));
    at[measured[m].to].push_back(static_cast<int>(m));
  }
  std::vector<int> piece(count, -1);
  poses.assign(count, Eigen::Vector3d::Zero());
  std::vector<std::vector<int>> members(count);
  for (int start = 0; start < count; ++start) {
    if (piece[start] >= 0) continue;
    piece[start] = start;
    std::deque<int> queue{start};
    while (!queue.empty()) {
      const int place = queue.front();
      queue.pop_front();
      members[start].push_back(place);
      for (int m : at[place]) {
        const RelativePoseMeasurement& link = measured[m];
        const bool forward = link.from == place;
        const int other = forward ? link.to : link.from;
        if (piece[other] >= 0) continue;
        piece[other] = start;
        poses[other] = forward ? compose(poses[place], link.translation_m, link.turn_rad)
                               : decompose(poses[place], link.translation_m, link.turn_rad);
        queue.push_back(other);
      }
    }
  }
  for (const RelativePoseMeasurement& link : measured) {
    if (!link.switchable || piece[link.from] == piece[link.to]) continue;
    // The later piece (by its first place) moves onto the earlier, which keeps its gauge.
    const bool to_moves = piece[link.to] > piece[link.from];
    const int kept = to_moves ? piece[link.from] : piece[link.to];
    const int moving = to_moves ? piece[link.to] : piece[link.from];
    const int anchor = to_moves ? link.to : link.from;
    const Eigen::Vector3d target =
        to_moves ? compose(poses[link.from], link.translation_m, link.turn_rad)
                 : decompose(poses[link.to], link.translation_m, link.turn_rad);
    const Eigen::Vector3d before = poses[anchor];
    for (int place : members[moving]) {
      poses[place] = moved(poses[place], before, target);
      piece[place] = kept;
    }
    members[kept].insert(members[kept].end(), members[moving].begin(), members[moving].end());
    members[moving].clear();
  }
  return piece;
}

ceres::Solver::Options solver_options(int max_iterations, int threads) {
  ceres::Solver::Options options;
  // Sparse Cholesky of the normal equations: each pose meets only its links' neighbours.
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = max_iterations;
  options.num_threads = threads;
  options.logging_type = ceres::SILENT;
  return options;
}

// A start nearer the truth than dead reckoning when the odometry's heading drifts: the headings
// first, from the turns alone (the odometry's and the revisits', a revisit's under a Cauchy loss
// of one standard deviation), then the positions with the headings held, the same way (LAGO's
// order, Carlone et al. 2014, made robust). Each piece's first place keeps its pose.
void heading_first_start(const std::vector<RelativePoseMeasurement>& measurements,
                         const std::vector<int>& piece, const PoseGraphParams& params,
                         std::vector<Eigen::Vector3d>& poses) {
  const int count = static_cast<int>(poses.size());
  std::vector<double> headings(count);
  for (int place = 0; place < count; ++place) headings[place] = poses[place].z();
  ceres::Problem turns;
  for (double& heading : headings) turns.AddParameterBlock(&heading, 1);
  for (int place = 0; place < count; ++place) {
    if (piece[place] == place) turns.SetParameterBlockConstant(&headings[place]);
  }
  for (const RelativePoseMeasurement& m : measurements) {
    turns.AddResidualBlock(new ceres::AutoDiffCostFunction<TurnResidual, 1, 1, 1>(
                               new TurnResidual(m.turn_rad, m.turn_stddev_rad)),
                           m.switchable ? new ceres::CauchyLoss(1.0) : nullptr, &headings[m.from],
                           &headings[m.to]);
  }
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options(params.max_iterations, params.threads), &turns, &summary);
  for (int place = 0; place < count; ++place) poses[place].z() = wrapped_angle(headings[place]);
  ceres::Problem positions;
  for (Eigen::Vector3d& pose : poses) {
    positions.AddParameterBlock(pose.data(), 3, new ceres::SubsetManifold(3, {2}));
  }
  for (int place = 0; place < count; ++place) {
    if (piece[place] == place) positions.SetParameterBlockConstant(poses[place].data());
  }
  for (const RelativePoseMeasurement& m : measurements) {
    positions.AddResidualBlock(
        new ceres::AutoDiffCostFunction<FixedCost, 3, 3, 3>(new FixedCost(m)),
        m.switchable ? new ceres::CauchyLoss(1.0) : nullptr, poses[m.from].data(),
        poses[m.to].data());
  }
  ceres::Solve(solver_options(params.max_iterations, params.threads), &positions, &summary);
}

}  // namespace

PoseGraphResult solve_pose_graph(int place_count,
                                 const std::vector<RelativePoseMeasurement>& measurements,
                                 const std::vector<SpringMeasurement>& springs,
                                 const LatticeParams& spring_params,
                                 const PoseGraphParams& params) {
  params.check();
  for (const RelativePoseMeasurement& m : measurements) {
    if (m.from < 0 || m.to < 0 || m.from >= place_count || m.to >= place_count || m.from == m.to) {
      throw UsageError("pose graph: a measurement between places " + std::to_string(m.from) +
                       " and " + std::to_string(m.to) + " of " + std::to_string(place_count));
    }
    if (!(m.along_stddev_m > 0.0 && m.across_stddev_m > 0.0 && m.turn_stddev_rad > 0.0)) {
      throw UsageError("pose graph: a measurement between places " + std::to_string(m.from) +
                       " and " + std::to_string(m.to) + " has a standard deviation ≤ 0");
    }
  }
  for (const SpringMeasurement& spring : springs) {
    if (spring.a < 0 || spring.b < 0 || spring.a >= place_count || spring.b >= place_count) {
      throw UsageError("pose graph: a spring between places " + std::to_string(spring.a) + " and " +
                       std::to_string(spring.b) + " of " + std::to_string(place_count));
    }
  }
  PoseGraphResult result;
  const std::vector<int> piece = dead_reckoning(place_count, measurements, result.poses);
  heading_first_start(measurements, piece, params, result.poses);

  ceres::Problem problem;
  for (Eigen::Vector3d& pose : result.poses) problem.AddParameterBlock(pose.data(), 3);
  // The gauge: each piece's first place holds its starting pose.
  for (int place = 0; place < place_count; ++place) {
    if (piece[place] == place) problem.SetParameterBlockConstant(result.poses[place].data());
  }
  std::size_t switchable = 0;
  for (const RelativePoseMeasurement& m : measurements) switchable += m.switchable ? 1 : 0;
  result.switches.assign(switchable, 1.0);
  std::size_t next_switch = 0;
  for (const RelativePoseMeasurement& m : measurements) {
    double* from = result.poses[m.from].data();
    double* to = result.poses[m.to].data();
    if (!m.switchable) {
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<FixedCost, 3, 3, 3>(new FixedCost(m)), nullptr, from, to);
      continue;
    }
    double* on = &result.switches[next_switch++];
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<SwitchedCost, 3, 3, 3, 1>(new SwitchedCost(m)), nullptr,
        from, to, on);
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SwitchPrior, 1, 1>(
                                 new SwitchPrior{params.switch_prior_stddev}),
                             nullptr, on);
    problem.SetParameterLowerBound(on, 0, 0.0);
    problem.SetParameterUpperBound(on, 0, 1.0);
  }

  // The springs: metres, Cauchy at loss_scale_m, as in the spring model (spring_lattice.hpp),
  // whose balance against motions in standard deviations they keep.
  for (const SpringMeasurement& spring : springs) {
    const double stiffness = used_stiffness(spring, spring_params);
    if (stiffness <= 0.0) continue;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PoseSpring, 1, 3, 3>(new PoseSpring{
                                 SpringResidual(spring.length_m, stiffness, spring.at_least)}),
                             new ceres::CauchyLoss(spring_params.loss_scale_m),
                             result.poses[spring.a].data(), result.poses[spring.b].data());
  }
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options(params.max_iterations, params.threads), &problem, &summary);
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.summary = summary.BriefReport();
  for (Eigen::Vector3d& pose : result.poses) pose.z() = wrapped_angle(pose.z());

  // Pieces by the measurements kept.
  std::vector<std::size_t> rank(place_count, 0), parent(place_count, 0);
  boost::disjoint_sets<std::size_t*, std::size_t*> pieces(rank.data(), parent.data());
  for (std::size_t place = 0; place < result.poses.size(); ++place) pieces.make_set(place);
  next_switch = 0;
  for (const RelativePoseMeasurement& m : measurements) {
    const bool kept = !m.switchable || result.switches[next_switch++] >= 0.5;
    if (kept) pieces.union_set(static_cast<std::size_t>(m.from), static_cast<std::size_t>(m.to));
  }
  for (std::size_t place = 0; place < result.poses.size(); ++place) {
    result.pieces += pieces.find_set(place) == place ? 1 : 0;
  }
  return result;
}

}  // namespace omninav::lattice
