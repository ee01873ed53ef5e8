#include "omninav/lattice/organise.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <string>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/evaluation/lattice_score.hpp"
#include "omninav/evaluation/render_database.hpp"
#include "omninav/io/sequence.hpp"
#include "omninav/lattice/confirmed_links.hpp"
#include "omninav/lattice/stiffness.hpp"
#include "omninav/sim/room.hpp"
#include "omninav/sim/world_loader.hpp"
#include "support/readme_room_tour.hpp"
#include "support/rendered_map.hpp"

namespace omninav::lattice {
namespace {

// A map of a 30 cm grid of the built-in room rendered at 360×45 (the grid of Menegatti et al. 2004,
// §3.3, Fig. 14; points inside furniture are left out, as a robot could not stand there), every
// image a place, headings from the truth, in the order a grid database lists them.
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
    // Good against the truth, so the quality (which does not see it) must trust it.
    EXPECT_TRUE(result.quality.trustworthy) << seed << ": " << result.quality.motions_off;
  }
}

// The full suite's panoramas: 360 x 45.
sim::RenderParams full_suite_render() {
  sim::RenderParams render;
  render.geometry.width_px = 360;
  render.geometry.height_px = 45;
  return render;
}

// A copy of `map` organised with `params`, scored against the truth.
evaluation::LatticeScore organised_copy(memory::VisualMemory map, const OrganiseParams& params) {
  organise(map, params);
  return *evaluation::score_lattice(map, false);
}

TEST(Organise, StepsAlongTheHeadingsHoldAZigZagAmongBoxes) {
  // The full suite's room-plain-s1 zig-zag every 60 cm (10 x 8 m, 16 boxes, plain walls), with
  // headings from the truth: among boxes the phases' fit of a 60 cm step is often tens of
  // degrees off, and the stream bends where it does. A robot drives forward, so with headings
  // good to a few degrees the steps along them hold the stream's shape.
  sim::RoomParams params;
  params.size_x_m = 10.0;
  params.size_y_m = 8.0;
  params.furniture_count = 16;
  params.plain_walls = true;
  params.seed = 1;
  const sim::World room = sim::make_room(params);
  sim::RenderParams render;
  render.geometry.width_px = 360;
  render.geometry.height_px = 45;
  const memory::VisualMemory explored = testing::rendered_run_map(
      room, render, "zigzag:x0=3.65,y0=2.95,x1=6.35,y1=4.75,rows=4,speed_m_s=0.2,fps=10,z_m=1", 0.6,
      "organise_test.cpp");
  ASSERT_EQ(explored.place_count(), 22u);
  OrganiseParams from_phases;
  from_phases.steps_along_heading = false;
  const evaluation::LatticeScore phases = organised_copy(explored, from_phases);
  const evaluation::LatticeScore headings = organised_copy(explored, {});
  std::cout << "zig-zag among boxes: steps from the phases " << phases.rmse.all << " spacings, "
            << phases.folded.size() << " folds; along the headings " << headings.rmse.all << ", "
            << headings.folded.size() << " of " << headings.neighbour_triangles << "\n";
  EXPECT_GT(phases.rmse.all, 1.0);  // the map is one the phases' steps get wrong
  EXPECT_LT(headings.rmse.all, 0.4);
  EXPECT_EQ(headings.folded.size(), 0u);
}

TEST(Organise, CompassHeadingsAreMadeConsistentAlongAZigZag) {
  // The full suite's room-s1 zig-zag every 30 cm, explored with the visual compass: it turns on
  // the spot at each row's end and the compass loses part of each turn (its headings end a
  // median 18 deg off, the 90th percentile 120 deg). Re-solved from the phases' turns between
  // near places, the headings hold the lattice.
  const sim::World world = sim::load_world("room:seed=1", sim::WorldsConfig{});
  sim::RenderParams render;
  render.geometry.width_px = 360;
  render.geometry.height_px = 45;
  const memory::VisualMemory explored = testing::explored_stream(
      testing::rendered_frames(
          world, render, "zigzag:x0=1.65,y0=1.45,x1=4.35,y1=3.55,rows=8,speed_m_s=0.2,fps=10,z_m=1",
          "run"),
      {0.3, memory::HeadingPolicy::kCompass}, "run", "organise_test.cpp");
  ASSERT_EQ(explored.place_count(), 80u);
  ASSERT_EQ(explored.place(40).heading_source, memory::HeadingSource::kCompass);
  OrganiseParams as_measured;
  as_measured.synchronise_compass_headings = false;
  const evaluation::LatticeScore compass = organised_copy(explored, as_measured);
  const evaluation::LatticeScore synchronised = organised_copy(explored, {});
  std::cout << "zig-zag with the compass's headings: " << compass.rmse.all << " spacings ("
            << compass.rmse.interior << " interior); synchronised " << synchronised.rmse.all << " ("
            << synchronised.rmse.interior << "), " << synchronised.folded.size() << " of "
            << synchronised.neighbour_triangles << " folds\n";
  EXPECT_GT(compass.rmse.all, 1.5);  // the compass's headings bend the lattice
  EXPECT_LT(synchronised.rmse.all, 0.7);
  EXPECT_LT(synchronised.rmse.interior, 0.45);
}

TEST(Organise, AGridDatabaseStatesItsSpacing) {
  // `omninav render` writes a grid database with BoB's `grid` metadata (separationMM); explored,
  // the map records the spacing, and organise takes its scale from it with no step given. The
  // scale is checked against the truth directly (the RMSE's alignment would hide a wrong one):
  // on the lattice, true neighbours 0.3 m apart must lie a median 0.3 m apart.
  const sim::World room = sim::make_room({});
  sim::RenderParams render;
  render.geometry.width_px = 360;
  render.geometry.height_px = 45;
  const std::filesystem::path folder = std::filesystem::temp_directory_path() /
                                       ("omninav_organise_grid_" + std::to_string(::getpid()));
  evaluation::render_database(sim::Renderer(room, render),
                              sim::make_trajectory("grid:nx=6,ny=5,spacing_m=0.3", room), folder,
                              "organise_test.cpp", true, 0);
  memory::VisualMemory map{memory::MapParameters{}};
  {
    std::unique_ptr<io::SequenceReader> reader = io::open_sequence(folder);
    ASSERT_EQ(reader->grid_spacing_m(), std::optional<double>(0.3));
    memory::explore_frames(map, {},
                           {.name = folder.string(),
                            .is_grid = true,
                            .frame_count = reader->size(),
                            .grid_spacing_m = reader->grid_spacing_m(),
                            .next = [&reader] { return reader->next(); }});
  }
  std::filesystem::remove_all(folder);
  ASSERT_EQ(map.grid_spacing_m(), std::optional<double>(0.3));
  const OrganiseResult result = organise(map, {});
  EXPECT_EQ(result.calibration.step_source, ScaleSource::kGrid);
  EXPECT_DOUBLE_EQ(result.calibration.step_m, 0.3);
  std::vector<double> neighbour_distances_m;
  for (std::size_t a = 0; a < map.place_count(); ++a) {
    for (std::size_t b = a + 1; b < map.place_count(); ++b) {
      const CameraPose& pa = *map.place(a).truth;
      const CameraPose& pb = *map.place(b).truth;
      if (std::abs(std::hypot(pa.x_m - pb.x_m, pa.y_m - pb.y_m) - 0.3) > 0.01) continue;
      neighbour_distances_m.push_back(
          (*map.place(a).lattice_position - *map.place(b).lattice_position).norm());
    }
  }
  ASSERT_GT(neighbour_distances_m.size(), 30u);
  EXPECT_NEAR(median(neighbour_distances_m), 0.3, 0.05);
  EXPECT_TRUE(result.quality.trustworthy);
}

// The full suite's grids of three families (worlds.yaml's room with plain walls, the office, the
// field seen from 1 m; 10 x 8 points 30 cm apart, as `omninav evaluate --suite full` renders them),
// against the truth: where the checked motions leave the grid in pieces, the pieces are joined by
// the pairs whose fit explains the two views best. Each bound lies below what joining by the
// most similar pairs (often look-alikes metres away) gives on the same grid: 3.40, 3.41 and 1.09
// spacings.
TEST(Organise, PiecesAreJoinedByTheBestFittingPairs) {
  struct Row {
    std::string world, grid;
    double bound;  // RMSE in spacings, joined by the best-fitting pairs
  };
  // Joined by the best-fitting pairs, the stored maps give 1.46, 2.86 and 0.90 spacings.
  const std::vector<Row> rows = {
      {"room:size_x_m=10,size_y_m=8,boxes=16,walls=plain,seed=1",
       "grid:x0=3.65,y0=2.95,nx=10,ny=8,spacing_m=0.3,z_m=1", 1.8},
      {"office:seed=2", "grid:x0=6.15,y0=4.65,nx=10,ny=8,spacing_m=0.3,z_m=1", 3.1},
      {"field:seed=2", "grid:x0=8.65,y0=8.95,nx=10,ny=8,spacing_m=0.3,z_m=1", 1.0}};
  for (const Row& row : rows) {
    const sim::World world = sim::load_world(row.world, sim::WorldsConfig{});
    memory::VisualMemory map =
        testing::rendered_grid_map(world, full_suite_render(), row.grid, "organise_test.cpp");
    const int pieces = organise(map, thirty_centimetres()).quality.pieces;
    const std::optional<evaluation::LatticeScore> score = evaluation::score_lattice(map, false);
    ASSERT_TRUE(score);
    std::cout << row.world << ": " << pieces << " pieces; RMSE " << score->rmse.all
              << " spacings\n";
    EXPECT_GT(pieces, 1) << row.world;
    EXPECT_LT(score->rmse.all, row.bound) << row.world;
  }
}

TEST(Organise, TheQualityTellsAFoldedLatticeFromAGoodOneWithoutTheTruth) {
  // The motions of the rendered grid against the lattice organise found (good: measured 0.35
  // spacings RMSE) and against the same lattice with its right half mirrored onto its left (a
  // fold, as look-alikes make): the quality sees the fold from the motions alone.
  memory::VisualMemory map = grid_map({}, "grid:nx=10,ny=8,spacing_m=0.3");
  const OrganiseResult result = organise(map, thirty_centimetres());
  EXPECT_TRUE(result.quality.trustworthy);
  EXPECT_EQ(result.quality.pieces, 1 + result.motion_joins);
  EXPECT_EQ(map.lattice_quality()->motions, result.quality.motions);
  std::cout << "good lattice: " << result.quality.motions_off << " of motions off, residual "
            << result.quality.motion_residual_steps << " steps\n";
  EXPECT_LT(result.quality.motions_off, OrganiseParams{}.max_motions_off);
  std::vector<Eigen::Vector2d> folded = result.lattice.positions;
  double middle_x = 0.0;
  for (const Eigen::Vector2d& p : folded) middle_x += p.x() / static_cast<double>(folded.size());
  for (Eigen::Vector2d& p : folded) {
    if (p.x() > middle_x) p.x() = 2.0 * middle_x - p.x();
  }
  const memory::LatticeQuality bad = measure_quality(folded, result.motions, result.motion_joins,
                                                     0.3, OrganiseParams{}.max_motions_off);
  std::cout << "folded lattice: " << bad.motions_off << " of motions off, residual "
            << bad.motion_residual_steps << " steps\n";
  EXPECT_FALSE(bad.trustworthy);
  EXPECT_GT(bad.motions_off, 2.0 * result.quality.motions_off);
  // Joins (pieces placed by look-alikes only) make any lattice untrustworthy.
  EXPECT_FALSE(measure_quality(result.lattice.positions, result.motions, 1, 0.3, 0.05).trustworthy);
}

TEST(Organise, TheQualityWarnsWhereTheTruthSaysTheLatticeIsWrong) {
  // The grids of the quick suite in three families (docs/lattice.md, Quality), at its 180 x 24
  // panoramas: the house (two rooms and a corridor; measured 6.9 spacings off, in 3 pieces), the
  // field at 10 cm (2.7 spacings, 31 % of motions off) and the room (0.33, none off). Whatever
  // the lattice, the verdict must agree with the truth: trustworthy within 0.7 spacings, not
  // beyond 1.5.
  struct Case {
    const char* world;
    const char* grid;
  };
  int wrong = 0;
  for (const Case& c : {Case{"house:rooms=2,room_min_m=2.5,room_max_m=3",
                             "grid:x0=0.369,y0=0.331,nx=8,ny=23,spacing_m=0.3,z_m=1"},
                        Case{"field", "grid:x0=8.95,y0=9.25,nx=8,ny=6,spacing_m=0.3,z_m=0.1"},
                        Case{"room", "grid:x0=1.95,y0=1.75,nx=8,ny=6,spacing_m=0.3,z_m=1"}}) {
    const sim::World world = sim::load_world(c.world, sim::WorldsConfig{});
    sim::RenderParams render;
    render.geometry.width_px = 180;
    render.geometry.height_px = 24;
    memory::VisualMemory map = testing::rendered_grid_map(world, render, c.grid, c.world);
    const OrganiseResult result = organise(map, thirty_centimetres());
    const std::optional<evaluation::LatticeScore> score = evaluation::score_lattice(map, false);
    ASSERT_TRUE(score);
    std::cout << c.world << ": RMSE " << score->rmse.all << " spacings; quality "
              << result.quality.motions_off << " of motions off, " << result.quality.pieces
              << " piece(s)\n";
    if (score->rmse.all < 0.7) {
      EXPECT_TRUE(result.quality.trustworthy) << c.world;
    }
    if (score->rmse.all > 1.5) {
      ++wrong;
      EXPECT_FALSE(result.quality.trustworthy) << c.world;
    }
  }
  if (wrong == 0) GTEST_SKIP() << "every lattice was right: no warning to check";
}

// Zig-zags of three families (the full suite's zig-zags at 30 cm in the room of seed 1, the
// office of seed 2 and the field seen from 1 m, four of their eight rows), a place every 30 cm,
// organised and judged against the renderer's poses: the interior within the target, 0.5
// spacing. Headings from the truth, to isolate the lattice from the compass (the full suite's
// compass headings bend the room's: docs/lattice.md). Measured, RMSE / interior in spacings and
// folds: room 0.41 / 0.13 / 1 (a row's end), office 0.16 / 0.11 / 0, field 0.16 / 0.07 / 0.
TEST(Organise, ZigZagsOfThreeFamiliesHoldTheirShape) {
  struct Row {
    std::string world, zigzag;
    std::size_t max_folds;
  };
  const std::vector<Row> rows = {
      {"room:seed=1", "zigzag:x0=1.65,y0=1.45,x1=4.35,y1=2.35,rows=4,speed_m_s=0.2,fps=10,z_m=1",
       1},
      {"office:seed=2", "zigzag:x0=6.15,y0=4.65,x1=8.85,y1=5.55,rows=4,speed_m_s=0.2,fps=10,z_m=1",
       0},
      {"field:seed=1", "zigzag:x0=8.65,y0=8.95,x1=11.35,y1=9.85,rows=4,speed_m_s=0.2,fps=10,z_m=1",
       0}};
  for (const Row& row : rows) {
    const sim::World world = sim::load_world(row.world, sim::WorldsConfig{});
    const memory::VisualMemory explored =
        testing::rendered_run_map(world, full_suite_render(), row.zigzag, 0.3, "organise_test.cpp");
    const evaluation::LatticeScore score = organised_copy(explored, {});
    std::cout << row.world << " zig-zag at 30 cm: RMSE " << score.rmse.all << " spacings, interior "
              << score.rmse.interior << ", " << score.folded.size() << " folds\n";
    EXPECT_LT(score.rmse.interior, 0.5) << row.world;
    EXPECT_LT(score.rmse.all, 0.5) << row.world;
    EXPECT_LE(score.folded.size(), row.max_folds) << row.world;
  }
}

TEST(Organise, AMapMadeByDrivingWithOdometryIsARobustPoseGraph) {
  memory::VisualMemory driven = testing::readme_room_tour(true);
  const OrganiseResult result = organise(driven, {});
  const std::optional<evaluation::LatticeScore> graph = evaluation::score_lattice(driven, false);
  memory::VisualMemory without_odometry = testing::readme_room_tour(false);
  const OrganiseResult springs = organise(without_odometry, {});
  const std::optional<evaluation::LatticeScore> spring_model =
      evaluation::score_lattice(without_odometry, false);
  ASSERT_TRUE(graph && spring_model);
  std::cout << "driven tour, " << driven.place_count() << " places: pose graph RMSE "
            << graph->rmse.all << " spacings (" << graph->rmse.interior << " interior), "
            << result.revisits << " revisits (" << result.revisits_switched_off
            << " switched off); spring model " << spring_model->rmse.all << " ("
            << spring_model->rmse.interior << ")\n";
  // Every consecutive pair is a travelled link; revisits join the lanes.
  EXPECT_EQ(result.travelled_links, static_cast<int>(driven.place_count()) - 1);
  EXPECT_GT(result.revisits, 0);
  EXPECT_EQ(springs.travelled_links, 0);  // without odometry: the spring model
  EXPECT_FALSE(springs.springs.empty());
  EXPECT_EQ(result.quality.pieces, 1);
  // Measured 0.26 (the spring model 0.29; a tour this small has no interior places): the
  // families where the pose graph wins are the look-alike ones (docs/evaluation.md).
  EXPECT_LT(graph->rmse.all, 0.45);
}

// lattice_bench's smallest driven tour: a 12.5 m square room furnished as the default one, driven
// in lanes 30 cm apart with 5 % wheel odometry, a place every 30 cm, headings from the truth.
memory::VisualMemory bench_tour() {
  static const std::vector<io::Frame> frames = [] {
    sim::RoomParams room;
    room.size_x_m = room.size_y_m = 12.5;
    room.furniture_count = 42;  // the default room's 8 boxes on 30 m²
    sim::RenderParams render;
    render.geometry.width_px = 360;
    render.geometry.height_px = 45;
    render.rays_per_pixel = 1;
    return testing::rendered_frames(
        sim::make_room(room), render,
        "tour:x0=1,y0=1,x1=11.5,y1=11.5,lane_m=0.3,speed_m_s=0.3,fps=1,turn_rate_deg_s=90,"
        "odometry_noise=0.05",
        "tour");
  }();
  return testing::explored_stream(frames, {0.3, memory::HeadingPolicy::kTruth, true}, "tour",
                                  "organise_test.cpp");
}

// A copy of `tour` (places, edges, spacing) with each place changed by `change` first.
memory::VisualMemory changed_copy(const memory::VisualMemory& tour,
                                  const std::function<void(std::size_t, memory::Place&)>& change) {
  memory::VisualMemory map{tour.parameters()};
  map.set_exploration_spacing_m(*tour.exploration_spacing_m());
  for (std::size_t i = 0; i < tour.place_count(); ++i) {
    memory::Place place = tour.place(i);
    change(i, place);
    map.add_place(place);
  }
  for (const memory::VisualMemory::EdgeRef& edge : tour.edges()) {
    map.add_edge(edge.from, edge.to, *edge.edge);
  }
  return map;
}

// How many of a map's confirmed revisits join places truly within 1.5 spacings of each other
// (true), and how many join places more than 2 spacings apart (look-alikes).
struct RevisitTruth {
  int near = 0;
  int far = 0;
};
RevisitTruth revisit_truth(const memory::VisualMemory& map) {
  std::vector<double> headings;
  for (std::size_t i = 0; i < map.place_count(); ++i) headings.push_back(*map.place(i).heading_rad);
  RevisitTruth truth;
  for (const MeasuredLink& link : confirmed_links(map, headings, 0.3, LinkParams{})) {
    if (link.kind != LinkKind::kRevisit) continue;
    const CameraPose& a = *map.place(link.places.first).truth;
    const CameraPose& b = *map.place(link.places.second).truth;
    const double apart = std::hypot(a.x_m - b.x_m, a.y_m - b.y_m) / 0.3;
    if (apart <= 1.5) ++truth.near;
    if (apart > 2.0) ++truth.far;
  }
  return truth;
}

// Revisits confirmed by their images, against the truth: on the bench tour the thumbnails' check
// lets in a fraction of the look-alikes the two fits' agreement does (which decides on the same
// map without thumbnails: look-alikes' fits can agree), and keeps nearly as many true revisits.
TEST(Organise, RevisitsAreConfirmedByTheirImages) {
  const memory::VisualMemory tour = bench_tour();
  const RevisitTruth by_images = revisit_truth(tour);
  const RevisitTruth by_fits = revisit_truth(
      changed_copy(tour, [](std::size_t, memory::Place& place) { place.thumbnail_png.clear(); }));
  std::cout << "bench tour revisits, true / look-alikes: by images " << by_images.near << " / "
            << by_images.far << ", by the two fits' agreement " << by_fits.near << " / "
            << by_fits.far << "\n";
  // Measured 265 / 10 by images, 280 / 67 by the fits.
  EXPECT_LT(3 * by_images.far, by_fits.far);
  EXPECT_GT(by_images.near, 0.9 * by_fits.near);
}

// How far the kept revisits' lengths are from their places' true distance, rms in spacings of
// 0.3 m: as the solve measured them, and as one spacing each.
struct RevisitLengthErrors {
  double by_parallax = 0.0;
  double by_spacing = 0.0;
  int revisits = 0;
};
RevisitLengthErrors revisit_length_errors(const memory::VisualMemory& map,
                                          const OrganiseResult& result) {
  RevisitLengthErrors errors;
  for (const MotionMeasurement& motion : result.motions) {
    if (motion.step) continue;  // the kept revisits
    const double truth = (map.place(motion.from).truth->floor_position() -
                          map.place(motion.to).truth->floor_position())
                             .norm();
    errors.by_parallax += std::pow(motion.length_m - truth, 2);
    errors.by_spacing += std::pow(0.3 - truth, 2);
    ++errors.revisits;
  }
  if (errors.revisits > 0) {
    errors.by_parallax = std::sqrt(errors.by_parallax / errors.revisits) / 0.3;
    errors.by_spacing = std::sqrt(errors.by_spacing / errors.revisits) / 0.3;
  }
  return errors;
}

// The map organised, its kept revisits' length errors and its lattice's RMSE against the truth,
// printed under `label`; the RMSE is NaN when the map cannot be scored.
struct ParallaxOutcome {
  RevisitLengthErrors errors;
  double rmse_all = std::numeric_limits<double>::quiet_NaN();
};
ParallaxOutcome organise_with_parallax(memory::VisualMemory& map, const std::string& label) {
  const OrganiseResult result = organise(map, {});
  const std::optional<evaluation::LatticeScore> score = evaluation::score_lattice(map, false);
  ParallaxOutcome outcome{revisit_length_errors(map, result)};
  if (!score) return outcome;
  outcome.rmse_all = score->rmse.all;
  std::cout << label << ", " << map.place_count() << " places, " << outcome.errors.revisits
            << " revisits kept: their length " << outcome.errors.by_parallax
            << " spacings rms off the truth by the parallax, " << outcome.errors.by_spacing
            << " as one spacing; lattice RMSE " << score->rmse.all << " spacings ("
            << score->rmse.interior << " interior)\n";
  return outcome;
}

// A revisit's length from its parallax, against the truth: nearer the distance between its
// places than one spacing is, and the lattice with it.
TEST(Organise, ARevisitIsAsLongAsItsParallaxSays) {
  memory::VisualMemory map = bench_tour();
  const ParallaxOutcome outcome = organise_with_parallax(map, "bench tour");
  ASSERT_GT(outcome.errors.revisits, 0);
  EXPECT_LT(outcome.errors.by_parallax, 0.8 * outcome.errors.by_spacing);
  // Measured 0.54. The lattice's RMSE moves with the odometry's noise: over odometry_seed 1-4
  // 0.54, 0.51, 0.57, 0.46 (before frames stopped leaping into the tour's corners: 0.42, 0.46,
  // 0.58, 0.71), so the bound is the spread's, not the 0.5 (lattice_bench measures that).
  EXPECT_LT(outcome.rmse_all, 0.6);
}

// The bench tour with its stored headings turned a quarter turn from half way on, as a compass
// that jumped: revisits between the two halves are fitted first at a turn 90° off the images'.
// Held there, the fit explains the difference by translation (parallaxes of radians, lengths of
// many spacings); fitted again at the phases' turn, whose fit explains the views better, the
// revisits are as long as their places are apart.
TEST(Organise, ARevisitsParallaxIsFittedAtTheTurnTheImagesBearOut) {
  const memory::VisualMemory tour = bench_tour();
  const std::size_t half = tour.place_count() / 2;
  memory::VisualMemory map = changed_copy(tour, [half](std::size_t i, memory::Place& place) {
    if (i >= half) place.heading_rad = wrap_angle(*place.heading_rad + kPi / 2);
  });
  const ParallaxOutcome outcome = organise_with_parallax(
      map, "bench tour, headings turned 90° from place " + std::to_string(half));
  ASSERT_GT(outcome.errors.revisits, 0);
  EXPECT_LT(outcome.errors.by_parallax, 0.8 * outcome.errors.by_spacing);
  // Measured 0.68 (2.34 with the parallax fitted at the headings' turn only; 0.44 with the
  // headings untouched, which the revisits' gates and the steps' fits also use).
  EXPECT_LT(outcome.rmse_all, 1.0);
}

// The README tour's compass drifts by 14° over the tour. A degree more or less of it from half
// way on, as another compass or another run would give, must not move the lattice: the revisits
// between the halves are fitted at the turn their images bear out, not only at the headings'.
// Before that, -0.9° from place 22 switched off one more revisit and took the RMSE from 0.35 to
// 0.52 spacings; -2° took it to 0.27.
TEST(Organise, ADegreeOfCompassDriftDoesNotMoveADrivenLattice) {
  const memory::VisualMemory tour = testing::readme_room_tour(true);
  const std::size_t half = tour.place_count() / 2;
  memory::VisualMemory untouched = tour;
  organise(untouched, {});
  const double rmse = evaluation::score_lattice(untouched, false)->rmse.all;
  for (const double drift_deg : {-2.0, -0.9, 0.9, 2.0}) {
    memory::VisualMemory drifted = changed_copy(tour, [&](std::size_t i, memory::Place& place) {
      if (i >= half) place.heading_rad = wrap_angle(*place.heading_rad + deg_to_rad(drift_deg));
    });
    organise(drifted, {});
    const double drifted_rmse = evaluation::score_lattice(drifted, false)->rmse.all;
    EXPECT_NEAR(drifted_rmse, rmse, 0.05) << drift_deg << "° from place " << half;
  }
  EXPECT_LT(rmse, 0.45);
}

TEST(Organise, ClearErrors) {
  memory::VisualMemory empty{memory::MapParameters{}};
  EXPECT_THROW(organise(empty, thirty_centimetres()), UsageError);
  memory::VisualMemory map = grid_map({}, "grid:nx=3,ny=1,spacing_m=0.3");
  EXPECT_THROW(organise(map, {}), UsageError);  // no step given, none in the map
}

// A value set in code, as Python's writable fields set it, is refused by organise() as the YAML
// loader refuses it in lattice.yaml, naming the key (OrganiseParams::check), before any work.
TEST(Organise, ParamsOutOfRangeAreRefusedBeforeAnyWork) {
  memory::VisualMemory memory;
  OrganiseParams params;
  params.range_fraction = 2.0;
  try {
    organise(memory, params);
    ADD_FAILURE() << "range_fraction 2 was accepted";
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find("organise.range_fraction"), std::string::npos);
  }
  params = {};
  params.lattice.max_iterations = 0;
  EXPECT_THROW(organise(memory, params), UsageError);
  EXPECT_NO_THROW(OrganiseParams{}.check());
}

}  // namespace
}  // namespace omninav::lattice
