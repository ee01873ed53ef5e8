#include "omninav/lattice/spring_lattice.hpp"

#include <ceres/ceres.h>

#include "motion_blocks.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/lattice/residuals.hpp"
#include "omninav/lattice/stiffness.hpp"

namespace omninav::lattice {
namespace {

void require_place(int place, int place_count, const std::string& what) {
  if (place < 0 || place >= place_count) {
    throw UsageError("lattice: " + what + " names place " + std::to_string(place) + " of " +
                     std::to_string(place_count));
  }
}

// Throws UsageError for a spring or motion that names no place, or a motion without length.
void check_measurements(int place_count, const std::vector<SpringMeasurement>& springs,
                        const std::vector<MotionMeasurement>& motions) {
  if (place_count < 1) throw UsageError("lattice: no places to arrange");
  for (const SpringMeasurement& spring : springs) {
    require_place(spring.a, place_count, "a spring");
    require_place(spring.b, place_count, "a spring");
  }
  for (const MotionMeasurement& motion : motions) {
    require_place(motion.from, place_count, "a motion constraint");
    require_place(motion.to, place_count, "a motion constraint");
    if (motion.from == motion.to || !(motion.length_m > 0.0)) {
      throw UsageError("lattice: a motion from place " + std::to_string(motion.from) + " to " +
                       std::to_string(motion.to) + " needs two places and a length > 0");
    }
  }
}

// The springs (Eq. 4) at least min_stiffness stiff (Eq. 5) as residual blocks; returns how many.
std::size_t add_springs(ceres::Problem& problem, const std::vector<SpringMeasurement>& springs,
                        const LatticeParams& params, ceres::LossFunction* loss,
                        std::vector<Eigen::Vector2d>& positions) {
  std::size_t kept = 0;
  for (const SpringMeasurement& spring : springs) {
    const double stiffness = used_stiffness(spring, params);
    if (stiffness <= 0.0) continue;
    problem.AddResidualBlock(SpringResidual::Create(spring.length_m, stiffness, spring.at_least),
                             loss, positions[spring.a].data(), positions[spring.b].data());
    ++kept;
  }
  return kept;
}

// The gauge, fixed explicitly. Translation: place 0 stays at the origin. Rotation (and
// reflection): the motion constraints fix them when there are any; otherwise the second place
// keeps the direction it starts in (its y = 0 after rotating the start so), and reflection is
// whatever the start had: distances alone cannot tell a lattice from its mirror image.
void fix_gauge(ceres::Problem& problem, bool has_motions, std::vector<Eigen::Vector2d>& positions) {
  problem.SetParameterBlockConstant(positions[0].data());
  if (has_motions) return;
  const Eigen::Vector2d second = positions[1];
  const double angle = std::atan2(second.y(), second.x());
  const Eigen::Rotation2Dd unrotate(-angle);
  for (Eigen::Vector2d& position : positions) position = unrotate * position;
  positions[1].y() = 0.0;
  problem.SetManifold(positions[1].data(), new ceres::SubsetManifold(2, {1}));
}

ceres::Solver::Options solver_options(const LatticeParams& params) {
  ceres::Solver::Options solver;
  // Conjugate gradients on the normal equations, not a sparse Cholesky: a place springs to its
  // most similar places, and the look-alikes among them lie anywhere on the map, so the factor
  // fills in: at 10,000 places the Cholesky did not finish, and on small grids CGNR gives the
  // same lattice (docs/evaluation.md, "Speed, measured").
  solver.linear_solver_type = ceres::CGNR;
  solver.preconditioner_type = ceres::JACOBI;
  // Each step's normal equations solved by CG to 30 % of their residual (an inexact Newton
  // step; Ceres' default forcing term is 10 %): the same lattices within 0.01 spacings, in a
  // fraction of the time (docs/evaluation.md, "Speed, measured").
  solver.eta = 0.3;
  // Unbending a dead-reckoned start takes many small steps; non-monotonic steps let the trust
  // region grow faster, and a 1e-4 relative cost change is far below what moves a place visibly.
  solver.use_nonmonotonic_steps = true;
  solver.function_tolerance = 1e-4;
  solver.max_num_iterations = params.max_iterations;
  solver.num_threads = params.threads;
  solver.logging_type = ceres::SILENT;
  return solver;
}

}  // namespace

double used_stiffness(const SpringMeasurement& spring, const LatticeParams& params) {
  const double negligible = negligible_length_m(params.correlation_range_m, params.min_stiffness);
  if (spring.a == spring.b || spring.length_m > negligible) return 0.0;  // Eq. 5: K < min_stiffness
  return params.spring_weight * spring_stiffness(spring.length_m, params.correlation_range_m);
}

LatticeResult solve_lattice(int place_count, const std::vector<SpringMeasurement>& springs,
                            const std::vector<MotionMeasurement>& motions,
                            const LatticeParams& params) {
  check_measurements(place_count, springs, motions);
  LatticeResult result;
  result.place_pairs = static_cast<std::size_t>(place_count) * (place_count - 1) / 2;
  result.springs_given = springs.size();
  result.motion_constraints = motions.size();
  result.positions = initial_positions(place_count, springs, motions);
  if (place_count == 1) {
    result.converged = true;
    return result;
  }

  // Cauchy rather than Huber: an aliased pair (two far places that look alike) gives a spring
  // that is simply wrong, and Cauchy's influence falls back towards zero for such residuals.
  // The losses are ours, not the problem's: Ceres deletes only those it was given in a block,
  // and a lattice without motions (or without springs) would leak the other.
  ceres::CauchyLoss spring_loss(params.loss_scale_m);
  // Motions measured between places that only look alike (a wrong neighbour) are outliers too.
  ceres::CauchyLoss motion_loss(params.motion_loss_scale);
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  result.springs_kept = add_springs(problem, springs, params, &spring_loss, result.positions);
  detail::add_motion_blocks(problem, motions, result.positions, &motion_loss);
  for (int place = 0; place < place_count; ++place) {
    if (!problem.HasParameterBlock(result.positions[place].data())) {
      throw UsageError("lattice: place " + std::to_string(place) +
                       " has no spring short enough to hold it and no motion constraint");
    }
  }
  fix_gauge(problem, !motions.empty(), result.positions);

  ceres::Solver::Summary summary;
  ceres::Solve(solver_options(params), &problem, &summary);
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.summary = summary.BriefReport();
  return result;
}

}  // namespace omninav::lattice
