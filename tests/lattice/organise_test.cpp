#include "omninav/lattice/organise.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "omninav/core/errors.hpp"
#include "omninav/evaluation/lattice_score.hpp"
#include "omninav/lattice/stiffness.hpp"
#include "omninav/sim/room.hpp"
#include "support/rendered_map.hpp"

namespace omninav::lattice {
namespace {

// A map of a 30 cm grid of the built-in room rendered at 360×45 (the grid of 001 §3.3, Fig. 14;
// points inside furniture are left out, as a robot could not stand there), every image a place,
// headings from the truth, in the order a grid database lists them.
memory::VisualMemory grid_map(const sim::RoomParams& room_params, const std::string& grid) {
  const sim::World room = sim::make_room(room_params);
  sim::RenderParams render;
  render.geometry.width_px = 360;
  render.geometry.height_px = 45;
  return testing::rendered_grid_map(room, render, grid, "organise_test.cpp");
}

OrganiseParams thirty_centimetres() {
  OrganiseParams params;
  params.step_m = 0.3;
  return params;
}

TEST(Organise, RecoversTheRenderedGridOfTheDefaultRoom) {
  memory::VisualMemory map = grid_map({}, "grid:nx=10,ny=8,spacing_m=0.3");
  const OrganiseResult result = organise(map, thirty_centimetres());
  const std::optional<evaluation::LatticeScore> score = evaluation::score_lattice(map, false);
  ASSERT_TRUE(score);
  std::cout << "default room, " << map.place_count() << " places: RMSE " << score->rmse.all
            << " spacings (" << score->rmse.interior << " interior); " << result.motions.size()
            << " motions\n";
  // Measured 0.35 (0.24 interior; 0.66 and 0.37 with free-turn motions and no look-alike
  // screening); springs alone (§3.2) gave 2.5 and folded it into a line.
  EXPECT_LT(score->rmse.all, 0.45);
  EXPECT_LT(score->rmse.interior, 0.35);
  EXPECT_GT(result.motions.size(), map.place_count());
  // Kept: exactly the springs at least min_stiffness stiff (Eq. 5) at the calibrated x₁.
  const auto stiff_enough = std::count_if(
      result.springs.begin(), result.springs.end(), [&](const SpringMeasurement& spring) {
        return spring_stiffness(spring.length_m, result.calibration.correlation_range_m) >=
               OrganiseParams{}.lattice.min_stiffness;
      });
  EXPECT_EQ(result.lattice.springs_kept, static_cast<std::size_t>(stiff_enough));
  EXPECT_LT(result.lattice.springs_kept, result.springs.size());
}

TEST(Organise, RecoversAFullTenByEightGrid) {
  // The default room has no free 2.7 × 2.1 m floor; this layout (seed 4, five boxes) has one.
  sim::RoomParams room;
  room.seed = 4;
  room.furniture_count = 5;
  memory::VisualMemory map = grid_map(room, "grid:x0=3.0,y0=0.3,nx=10,ny=8,spacing_m=0.3");
  ASSERT_EQ(map.place_count(), 80u);
  organise(map, thirty_centimetres());
  const std::optional<evaluation::LatticeScore> score = evaluation::score_lattice(map, false);
  ASSERT_TRUE(score);
  std::cout << "10 x 8 grid: RMSE " << score->rmse.all << " spacings (" << score->rmse.interior
            << " interior of " << score->rmse.interior_count << ")\n";
  // Measured 0.24 interior, 0.37 overall; the target (docs/lattice.md) is 0.35 interior.
  EXPECT_LT(score->rmse.interior, 0.35);
  EXPECT_LT(score->rmse.all, 0.45);
}

TEST(Organise, AZigZagEverySixtyCentimetresDoesNotFold) {
  // Fig. 16: a 540 x 540 cm square walked in a zig-zag, a place every 60 cm, here in an empty
  // 7 x 7 m room (textured walls only: periodic enough that far places look alike). At 60 cm
  // two consecutive places look no nearer than places metres apart (docs/lattice.md), so only
  // the stream's steps, and motions that are not a look-alike's, can keep the rows apart. In
  // the room of seed 11, look-alikes along the first row pass the residual test and only the
  // check against the steps drops them (1 fold without it).
  for (const unsigned seed : {1u, 11u}) {
    sim::RoomParams empty;
    empty.size_x_m = 7.0;
    empty.size_y_m = 7.0;
    empty.furniture_count = 0;
    empty.seed = seed;
    const sim::World room = sim::make_room(empty);
    sim::RenderParams render;
    render.geometry.width_px = 360;
    render.geometry.height_px = 45;
    memory::VisualMemory map = testing::rendered_run_map(
        room, render, "zigzag:x0=0.8,y0=0.8,x1=6.2,y1=6.2,rows=10,speed_m_s=0.3,fps=2", 0.6,
        "organise_test.cpp");
    ASSERT_EQ(map.place_count(), 100u);
    const OrganiseResult result = organise(map, {});  // the scale from the map
    EXPECT_EQ(result.calibration.step_source, ScaleSource::kMap);
    EXPECT_DOUBLE_EQ(result.calibration.step_m, 0.6);
    const auto steps = std::count_if(result.motions.begin(), result.motions.end(),
                                     [](const MotionMeasurement& motion) { return motion.step; });
    const std::optional<evaluation::LatticeScore> score = evaluation::score_lattice(map, false);
    ASSERT_TRUE(score);
    std::cout << "zig-zag at 60 cm, room seed " << seed << ": RMSE " << score->rmse.all
              << " spacings, " << score->folded.size() << " of " << score->neighbour_triangles
              << " neighbour triangles folded; " << steps << " steps, " << result.motions.size()
              << " motions, " << result.look_alikes_dropped << " look-alikes dropped\n";
    EXPECT_GE(steps, 90) << seed;
    EXPECT_GT(score->neighbour_triangles, 150) << seed;
    EXPECT_EQ(score->folded.size(), 0u) << seed;
    EXPECT_LT(score->rmse.all, 0.5) << seed;
  }
}

TEST(Organise, ClearErrors) {
  memory::VisualMemory empty{memory::MapParameters{}};
  EXPECT_THROW(organise(empty, thirty_centimetres()), UsageError);
  memory::VisualMemory map = grid_map({}, "grid:nx=3,ny=1,spacing_m=0.3");
  EXPECT_THROW(organise(map, {}), UsageError);  // no step given, none in the map
}

}  // namespace
}  // namespace omninav::lattice
