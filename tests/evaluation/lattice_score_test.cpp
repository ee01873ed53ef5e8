#include "omninav/evaluation/lattice_score.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace omninav::evaluation {
namespace {

// A 5 x 3 grid of places 0.5 m apart, each with its truth and a lattice position at `offset`
// from it (the lattice shifted and turned by a quarter, which the alignment removes).
memory::VisualMemory grid(const std::vector<Eigen::Vector2d>& offsets = {}) {
  memory::VisualMemory memory{memory::MapParameters{}};
  for (int i = 0; i < 15; ++i) {
    memory::Place place;
    place.signature.rows = 1;  // what the report reads is truth and lattice; any signature does
    place.signature.components = 15;
    place.signature.width_px = 32;
    place.signature.magnitude.assign(15, 1.0f);
    place.signature.phase_rad.assign(15, 0.0f);
    const double x = 0.5 * (i % 5), y = 0.5 * (i / 5);
    place.truth = CameraPose{x, y, 1.0, 0.0, 0.0, 0.0};
    Eigen::Vector2d at(x, y);
    if (static_cast<std::size_t>(i) < offsets.size()) at += offsets[i];
    place.lattice_position = Eigen::Vector2d(3.0 - at.y(), 1.0 + at.x());
    memory.add_place(std::move(place));
  }
  return memory;
}

TEST(LatticeScore, TheTruthHasNoFolds) {
  const std::optional<LatticeScore> evaluation = score_lattice(grid(), false);
  ASSERT_TRUE(evaluation);
  EXPECT_NEAR(evaluation->rmse.all, 0.0, 1e-9);
  // Eight squares, two triangles each; their diagonals (1.41 spacings) are within 1.5.
  EXPECT_EQ(evaluation->neighbour_triangles, 16);
  EXPECT_TRUE(evaluation->folded.empty());
}

TEST(LatticeScore, APlaceMovedPastItsNeighbourIsAFold) {
  // Place 6 (an interior place at 0.5, 0.5) moved to beyond place 7 (1.0, 0.5).
  std::vector<Eigen::Vector2d> offsets(15, Eigen::Vector2d::Zero());
  offsets[6] = Eigen::Vector2d(0.7, 0.05);
  const std::optional<LatticeScore> evaluation = score_lattice(grid(offsets), false);
  ASSERT_TRUE(evaluation);
  ASSERT_FALSE(evaluation->folded.empty());
  for (const std::array<std::size_t, 3>& triangle : evaluation->folded) {
    EXPECT_NE(std::find(triangle.begin(), triangle.end(), 6u), triangle.end());
  }
  // A nudge that keeps every triangle's orientation is no fold.
  offsets[6] = Eigen::Vector2d(0.1, -0.1);
  EXPECT_TRUE(score_lattice(grid(offsets), false)->folded.empty());
}

TEST(LatticeScore, AMirroredLatticeFoldsEverywhereUnlessReflectionIsAllowed) {
  memory::VisualMemory mirrored = grid();
  std::vector<Eigen::Vector2d> mirror_image;
  for (std::size_t i = 0; i < mirrored.place_count(); ++i) {
    mirror_image.push_back(
        mirrored.place(i).lattice_position->cwiseProduct(Eigen::Vector2d(-1, 1)));
  }
  mirrored.set_lattice_positions(mirror_image);
  EXPECT_EQ(score_lattice(mirrored, false)->folded.size(), 16u);
  EXPECT_TRUE(score_lattice(mirrored, true)->folded.empty());
}

}  // namespace
}  // namespace omninav::evaluation
