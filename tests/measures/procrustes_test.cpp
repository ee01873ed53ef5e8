#include "omninav/measures/procrustes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::measures {
namespace {

// An irregular set: no symmetry, so its mirror image is not a rotation of it.
std::vector<Eigen::Vector2d> irregular_points() {
  return {{0.0, 0.0}, {1.0, 0.2}, {2.3, -0.4}, {0.4, 1.7}, {-1.1, 0.9}, {1.8, 2.6}, {-0.5, -1.3}};
}

std::vector<Eigen::Vector2d> transformed(const std::vector<Eigen::Vector2d>& points, double scale,
                                         double rotation_rad, const Eigen::Vector2d& translation,
                                         bool mirror) {
  const Eigen::Matrix2d m = mirror ? Eigen::Matrix2d(Eigen::Vector2d(1.0, -1.0).asDiagonal())
                                   : Eigen::Matrix2d::Identity();
  const Eigen::Matrix2d linear = scale * Eigen::Rotation2Dd(rotation_rad).toRotationMatrix() * m;
  std::vector<Eigen::Vector2d> out;
  for (const Eigen::Vector2d& p : points) out.push_back(linear * p + translation);
  return out;
}

TEST(Procrustes, RecoversAKnownSimilarity) {
  const std::vector<Eigen::Vector2d> from = irregular_points();
  const Eigen::Vector2d t(3.0, -1.0);
  for (double angle_deg : {0.0, 37.0, -120.0, 179.0, 200.0}) {
    const double angle = deg_to_rad(angle_deg);
    const std::vector<Eigen::Vector2d> onto = transformed(from, 2.5, angle, t, false);
    const ProcrustesResult result = align_similarity(from, onto);
    EXPECT_LT(result.rmse, 1e-12) << angle_deg;
    EXPECT_NEAR(result.transform.scale, 2.5, 1e-12);
    EXPECT_NEAR(signed_difference(result.transform.rotation_rad, angle), 0.0, 1e-12) << angle_deg;
    EXPECT_NEAR((result.transform.translation - t).norm(), 0.0, 1e-12);
    EXPECT_FALSE(result.transform.reflected);
    ASSERT_EQ(result.aligned.size(), from.size());
    for (std::size_t i = 0; i < from.size(); ++i) {
      EXPECT_NEAR((result.aligned[i] - onto[i]).norm(), 0.0, 1e-12);
      EXPECT_NEAR((result.transform.apply(from[i]) - onto[i]).norm(), 0.0, 1e-12);
    }
  }
}

TEST(Procrustes, RecoversAReflectionWhenAllowed) {
  const std::vector<Eigen::Vector2d> from = irregular_points();
  const double angle = deg_to_rad(-65.0);
  const std::vector<Eigen::Vector2d> onto =
      transformed(from, 0.4, angle, Eigen::Vector2d(-2.0, 5.0), true);
  const ProcrustesResult result = align_similarity(from, onto, {.allow_reflection = true});
  EXPECT_LT(result.rmse, 1e-12);
  EXPECT_TRUE(result.transform.reflected);
  EXPECT_NEAR(result.transform.scale, 0.4, 1e-12);
  EXPECT_NEAR(signed_difference(result.transform.rotation_rad, angle), 0.0, 1e-12);
  EXPECT_NEAR(result.transform.linear.determinant(), -0.16, 1e-12);
}

TEST(Procrustes, ReflectedSetDoesNotAlignWhenReflectionIsForbidden) {
  const std::vector<Eigen::Vector2d> from = irregular_points();
  const std::vector<Eigen::Vector2d> onto =
      transformed(from, 1.0, deg_to_rad(30.0), Eigen::Vector2d(1.0, 1.0), true);
  const ProcrustesResult result = align_similarity(from, onto);  // reflection forbidden
  EXPECT_FALSE(result.transform.reflected);
  EXPECT_GT(result.transform.linear.determinant(), 0.0);
  // The points spread over about 1.2 units RMS around their centroid; the best proper
  // rotation of a mirrored irregular set leaves an error of a sizeable share of that.
  EXPECT_GT(result.rmse, 0.3);
}

TEST(Procrustes, ReflectionAllowedStillPrefersTheProperFit) {
  const std::vector<Eigen::Vector2d> from = irregular_points();
  const std::vector<Eigen::Vector2d> onto =
      transformed(from, 1.5, deg_to_rad(10.0), Eigen::Vector2d::Zero(), false);
  const ProcrustesResult result = align_similarity(from, onto, {.allow_reflection = true});
  EXPECT_FALSE(result.transform.reflected);
  EXPECT_LT(result.rmse, 1e-12);
}

TEST(Procrustes, RigidWhenScaleIsNotAllowed) {
  const std::vector<Eigen::Vector2d> from = irregular_points();
  const std::vector<Eigen::Vector2d> onto =
      transformed(from, 1.0, deg_to_rad(75.0), Eigen::Vector2d(0.5, 0.0), false);
  const ProcrustesResult rigid = align_similarity(from, onto, {.allow_scale = false});
  EXPECT_LT(rigid.rmse, 1e-12);
  EXPECT_NEAR(rigid.transform.scale, 1.0, 1e-12);
  // Twice as large a target cannot be matched without scale.
  const std::vector<Eigen::Vector2d> larger =
      transformed(from, 2.0, deg_to_rad(75.0), Eigen::Vector2d(0.5, 0.0), false);
  EXPECT_GT(align_similarity(from, larger, {.allow_scale = false}).rmse, 0.5);
  EXPECT_LT(align_similarity(from, larger).rmse, 1e-12);
}

TEST(Procrustes, LeastSquaresWithNoise) {
  // Noise of ±0.01 on the target: the fit error is of that size, the transform close.
  std::vector<Eigen::Vector2d> onto =
      transformed(irregular_points(), 2.0, 0.3, Eigen::Vector2d(1.0, 2.0), false);
  for (std::size_t i = 0; i < onto.size(); ++i) onto[i].x() += (i % 2 == 0 ? 0.01 : -0.01);
  const ProcrustesResult result = align_similarity(irregular_points(), onto);
  EXPECT_LT(result.rmse, 0.01);
  EXPECT_GT(result.rmse, 0.001);
  EXPECT_NEAR(result.transform.scale, 2.0, 0.01);
  EXPECT_NEAR(result.transform.rotation_rad, 0.3, 0.01);
}

TEST(Procrustes, RejectsDegenerateInput) {
  const std::vector<Eigen::Vector2d> same = {{1.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}};
  const std::vector<Eigen::Vector2d> three = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
  EXPECT_THROW(align_similarity(same, three), UsageError);
  EXPECT_THROW(align_similarity(three, std::vector<Eigen::Vector2d>(2)), UsageError);
  EXPECT_THROW(align_similarity(std::vector<Eigen::Vector2d>{{0.0, 0.0}},
                                std::vector<Eigen::Vector2d>{{1.0, 0.0}}),
               UsageError);
  std::vector<Eigen::Vector2d> with_nan = three;
  with_nan[1].y() = NAN;
  EXPECT_THROW(align_similarity(with_nan, three), UsageError);
}

// A 3×3 grid, spacing 0.3 m; node 4 is the only interior node.
//   6 7 8
//   3 4 5
//   0 1 2
std::vector<Eigen::Vector2d> grid_3x3(double spacing) {
  std::vector<Eigen::Vector2d> grid;
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 3; ++column) grid.emplace_back(spacing * column, spacing * row);
  }
  return grid;
}

TEST(SplitRmse, InteriorAndBoundaryByHand) {
  const double spacing = 0.3;
  const std::vector<Eigen::Vector2d> truth = grid_3x3(spacing);
  std::vector<Eigen::Vector2d> aligned = truth;
  aligned[4] += Eigen::Vector2d(0.03, 0.04);  // interior node off by 0.05 m
  aligned[0] += Eigen::Vector2d(0.06, 0.0);   // one boundary node off by 0.06 m
  const std::vector<std::size_t> boundary = {0, 1, 2, 3, 5, 6, 7, 8};

  const SplitRmse split = split_rmse_in_spacing(aligned, truth, boundary, spacing);
  EXPECT_EQ(split.interior_count, 1u);
  EXPECT_EQ(split.boundary_count, 8u);
  // interior: 0.05 / 0.3; boundary: sqrt(0.06²/8) / 0.3; all: sqrt((0.05² + 0.06²)/9) / 0.3.
  EXPECT_NEAR(split.interior, 0.05 / 0.3, 1e-12);
  EXPECT_NEAR(split.boundary, std::sqrt(0.0036 / 8.0) / 0.3, 1e-12);
  EXPECT_NEAR(split.all, std::sqrt(0.0061 / 9.0) / 0.3, 1e-12);

  const std::vector<std::size_t> interior = {4};
  EXPECT_NEAR(rmse_over(aligned, truth, interior), 0.05, 1e-12);
  EXPECT_NEAR(rmse_in_spacing(aligned, truth, interior, spacing), 0.05 / 0.3, 1e-12);
}

TEST(SplitRmse, EmptySubsetIsNaNAndBadIndicesThrow) {
  const std::vector<Eigen::Vector2d> truth = grid_3x3(1.0);
  const std::vector<std::size_t> everything = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  const SplitRmse split = split_rmse_in_spacing(truth, truth, everything, 1.0);
  EXPECT_TRUE(std::isnan(split.interior));
  EXPECT_EQ(split.boundary, 0.0);
  EXPECT_EQ(split.interior_count, 0u);
  EXPECT_THROW(split_rmse_in_spacing(truth, truth, std::vector<std::size_t>{9}, 1.0), UsageError);
  EXPECT_THROW(rmse_in_spacing(truth, truth, everything, 0.0), UsageError);
  EXPECT_THROW(rmse_over(truth, grid_3x3(1.0), std::vector<std::size_t>{12}), UsageError);
}

TEST(SplitRmse, AfterAlignment) {
  // The lattice use: a lattice in arbitrary units, turned and mirrored, with its interior
  // node displaced; align with reflection allowed, then split the error.
  const double spacing = 0.3;
  const std::vector<Eigen::Vector2d> truth = grid_3x3(spacing);
  std::vector<Eigen::Vector2d> lattice =
      transformed(truth, 10.0, deg_to_rad(140.0), Eigen::Vector2d(4.0, 4.0), true);
  const ProcrustesResult exact = align_similarity(lattice, truth, {.allow_reflection = true});
  const std::vector<std::size_t> boundary = {0, 1, 2, 3, 5, 6, 7, 8};
  const SplitRmse split = split_rmse_in_spacing(exact.aligned, truth, boundary, spacing);
  EXPECT_NEAR(split.all, 0.0, 1e-12);
  EXPECT_NEAR(split.interior, 0.0, 1e-12);
  // The centre node moved: its centroid shift is shared by all, but it stays the worst.
  lattice[4] += Eigen::Vector2d(1.0, 0.0);
  const ProcrustesResult moved = align_similarity(lattice, truth, {.allow_reflection = true});
  const SplitRmse moved_split = split_rmse_in_spacing(moved.aligned, truth, boundary, spacing);
  EXPECT_GT(moved_split.interior, moved_split.boundary);
  EXPECT_NEAR(moved_split.all, moved.rmse / spacing, 1e-12);
}

}  // namespace
}  // namespace omninav::measures
