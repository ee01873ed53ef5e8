#include "omninav/lattice/spring_lattice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "omninav/core/errors.hpp"
#include "omninav/lattice/stiffness.hpp"
#include "omninav/measures/procrustes.hpp"

namespace omninav::lattice {
namespace {

constexpr double kSpacing = 0.3;

// A nx × ny grid walked row by row, boustrophedon, as an exploring robot would.
std::vector<Eigen::Vector2d> zigzag_grid(int nx, int ny, double spacing) {
  std::vector<Eigen::Vector2d> truth;
  for (int iy = 0; iy < ny; ++iy) {
    for (int i = 0; i < nx; ++i) {
      const int ix = iy % 2 == 0 ? i : nx - 1 - i;
      truth.emplace_back(ix * spacing, iy * spacing);
    }
  }
  return truth;
}

std::vector<SpringMeasurement> springs_from(const std::vector<Eigen::Vector2d>& truth,
                                            double max_length, double relative_noise,
                                            unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, relative_noise);
  std::vector<SpringMeasurement> springs;
  for (int a = 0; a < static_cast<int>(truth.size()); ++a) {
    for (int b = a + 1; b < static_cast<int>(truth.size()); ++b) {
      const double length = (truth[a] - truth[b]).norm();
      if (length <= max_length) springs.push_back({a, b, length * (1.0 + noise(random))});
    }
  }
  return springs;
}

std::vector<MotionMeasurement> motions_from(const std::vector<Eigen::Vector2d>& truth,
                                            double stddev, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, stddev);
  std::vector<MotionMeasurement> motions;
  for (int i = 0; i + 1 < static_cast<int>(truth.size()); ++i) {
    const Eigen::Vector2d step = truth[i + 1] - truth[i];
    motions.push_back({i, i + 1, std::atan2(step.y(), step.x()) + noise(random), step.norm(),
                       std::max(stddev, 0.02), 0.3 * step.norm()});
  }
  return motions;
}

double rmse_in_spacing(const std::vector<Eigen::Vector2d>& positions,
                       const std::vector<Eigen::Vector2d>& truth) {
  measures::ProcrustesParams params;
  params.allow_reflection = true;  // distances alone cannot tell a lattice from its mirror image
  return measures::align_similarity(positions, truth, params).rmse / kSpacing;
}

TEST(SpringLattice, ExactDistancesRecoverTheGridUpToTheGauge) {
  const std::vector<Eigen::Vector2d> truth = zigzag_grid(6, 5, kSpacing);
  LatticeParams params;
  params.correlation_range_m = 0.9;
  const LatticeResult result =
      solve_lattice(static_cast<int>(truth.size()), springs_from(truth, 0.9, 0.0, 1), {}, params);
  EXPECT_TRUE(result.converged) << result.summary;
  EXPECT_LT(rmse_in_spacing(result.positions, truth), 1e-4);
  EXPECT_EQ(result.positions[0], Eigen::Vector2d::Zero());  // the gauge: place 0 at the origin
  EXPECT_NEAR(result.positions[1].y(), 0.0, 1e-12);         // and place 1 on the +x axis
}

TEST(SpringLattice, NoisyDistancesStayWithinABound) {
  // 10 % distance noise, as §3.4 reports for its experiment.
  const std::vector<Eigen::Vector2d> truth = zigzag_grid(10, 8, kSpacing);
  LatticeParams params;
  params.correlation_range_m = 0.9;
  for (unsigned seed : {1u, 2u, 3u}) {
    const LatticeResult result = solve_lattice(static_cast<int>(truth.size()),
                                               springs_from(truth, 1.2, 0.1, seed), {}, params);
    // Bound: measured ≈ 0.1 spacing; 0.25 leaves room for other seeds, a fold costs > 1.
    EXPECT_LT(rmse_in_spacing(result.positions, truth), 0.25) << "seed " << seed;
  }
}

TEST(SpringLattice, MotionConstraintsFixTheFrameAndUnfoldAPeriodicCorridor) {
  // A corridor of 24 places, 0.3 m apart, whose appearance repeats every 8 places: places 8 m
  // apart look alike, so their similarity says "near" (a short, stiff, wrong spring).
  std::vector<Eigen::Vector2d> truth;
  for (int i = 0; i < 24; ++i) truth.emplace_back(i * kSpacing, 0.0);
  std::vector<SpringMeasurement> springs = springs_from(truth, 0.9, 0.05, 4);
  for (int i = 0; i < 24; ++i) {
    for (int j = i + 8; j < 24; j += 8) springs.push_back({i, j, 0.1});
  }
  LatticeParams params;
  params.correlation_range_m = 0.9;
  const LatticeResult folded = solve_lattice(24, springs, {}, params);
  const LatticeResult unfolded = solve_lattice(24, springs, motions_from(truth, 0.1, 5), params);
  EXPECT_GT(rmse_in_spacing(folded.positions, truth), 1.0);    // aliasing folds the corridor
  EXPECT_LT(rmse_in_spacing(unfolded.positions, truth), 0.3);  // motion directions unfold it
  // With motions the frame is the first place's: the corridor runs along +x, not mirrored.
  EXPECT_GT(unfolded.positions.back().x(), 5.0);
  EXPECT_NEAR(unfolded.positions.back().y(), 0.0, 0.5);
}

TEST(SpringLattice, NegligibleSpringsAreDroppedAndCounted) {
  const std::vector<Eigen::Vector2d> truth = zigzag_grid(8, 6, kSpacing);
  const std::vector<SpringMeasurement> all = springs_from(truth, 100.0, 0.0, 1);
  LatticeParams params;
  params.correlation_range_m = 0.6;
  params.min_stiffness = 1e-3;
  const LatticeResult result = solve_lattice(static_cast<int>(truth.size()), all, {}, params);
  EXPECT_EQ(result.springs_given, all.size());
  std::size_t expected_kept = 0;
  for (const SpringMeasurement& spring : all)
    expected_kept += spring.length_m <= negligible_length_m(0.6, 1e-3);
  EXPECT_EQ(result.springs_kept, expected_kept);
  EXPECT_LT(result.springs_kept, all.size() / 2);
  EXPECT_LT(rmse_in_spacing(result.positions, truth), 1e-3);
}

TEST(SpringLattice, SaturatedSpringsThatOnlyPushDoNotCollapseTheLattice) {
  // Beyond a short range a dissimilarity saturates: every far pair reads about the same short
  // length (here 0.5 m, whatever the truth). Two-sided, those springs pull the grid together;
  // as lower bounds (at_least) they are all satisfied by the true layout and leave it alone.
  const std::vector<Eigen::Vector2d> truth = zigzag_grid(10, 8, kSpacing);
  std::vector<SpringMeasurement> springs = springs_from(truth, 0.45, 0.0, 1);
  const std::size_t near = springs.size();
  for (int a = 0; a < static_cast<int>(truth.size()); ++a) {
    for (int b = a + 1; b < static_cast<int>(truth.size()); ++b) {
      if ((truth[a] - truth[b]).norm() > 0.45) springs.push_back({a, b, 0.5});
    }
  }
  LatticeParams params;
  params.correlation_range_m = 0.9;
  const int count = static_cast<int>(truth.size());
  const LatticeResult pulled = solve_lattice(count, springs, {}, params);
  for (std::size_t i = near; i < springs.size(); ++i) springs[i].at_least = true;
  const LatticeResult pushed = solve_lattice(count, springs, {}, params);
  EXPECT_GT(rmse_in_spacing(pulled.positions, truth), 1.0);   // measured 1.75: collapsed
  EXPECT_LT(rmse_in_spacing(pushed.positions, truth), 1e-3);  // measured 5e-9
}

TEST(SpringLattice, BadInputIsAClearError) {
  EXPECT_THROW(solve_lattice(0, {}, {}), UsageError);
  EXPECT_THROW(solve_lattice(3, {{0, 5, 1.0}}, {}), UsageError);
  // Place 2 is held by nothing: the lattice would be undetermined.
  EXPECT_THROW(solve_lattice(3, {{0, 1, 0.3}}, {}), UsageError);
  const LatticeResult single = solve_lattice(1, {}, {});
  EXPECT_EQ(single.positions.size(), 1u);
}

}  // namespace
}  // namespace omninav::lattice
