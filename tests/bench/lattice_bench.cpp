// The lattice's speed (targets: 1,000 places organised in ≤ 2 s, 10,000 in ≤ 30 s on one
// core; a driven map's 10,000 in ≤ 10 s at RMSE ≤ 0.5 spacings). "Organised" is the whole of
// lattice::organise: calibration, springs and motions from the signatures, the start, the Ceres
// solve. The maps are rendered: a square grid of places 30 cm apart in a built-in room sized to
// hold it (furniture in proportion to the floor; grid points inside furniture are left out), 360 ×
// 45 panoramas, one anti-aliasing ray, headings from the truth, in the order a grid database lists
// them: what `omninav render --trajectory grid:...` and `omninav explore` give. Rendering is setup,
// not timed; the counters say how many places, springs (offered, kept, of all pairs) and motions
// there were, and the RMSE against the truth. Beside them, maps made by driving: a tour of the same
// rooms in lanes 30 cm apart with 5 % wheel odometry, a place every 30 cm the odometry measured
// (`explore --every-m 0.3
// --odometry`), organised as a pose graph.
// Run: taskset -c 1 build/bin/lattice_bench
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>

#include "omninav/evaluation/lattice_score.hpp"
#include "omninav/lattice/organise.hpp"
#include "omninav/sim/room.hpp"
#include "support/rendered_map.hpp"

namespace {

namespace evaluation = omninav::evaluation;
namespace lattice = omninav::lattice;
namespace memory = omninav::memory;
namespace sim = omninav::sim;

constexpr double kSpacing = 0.3;

constexpr double kMarginM = 1.0;  // between the grid (or the tour) and the walls

// The built-in room that holds a side × side grid, furnished at the default room's density
// (8 boxes on 30 m²).
sim::World room_for(int side) {
  sim::RoomParams room;
  room.size_x_m = room.size_y_m = (side - 1) * kSpacing + 2 * kMarginM;
  room.furniture_count = static_cast<int>(std::lround(8.0 * room.size_x_m * room.size_y_m / 30.0));
  return sim::make_room(room);
}

// 360 × 45 panoramas, one ray a pixel.
sim::RenderParams bench_render() {
  sim::RenderParams render;
  render.geometry.width_px = 360;
  render.geometry.height_px = 45;
  render.rays_per_pixel = 1;
  return render;
}

// The map of a side × side grid, rendered once per process.
const memory::VisualMemory& grid_map(int side) {
  static std::map<int, memory::VisualMemory> maps;
  const auto found = maps.find(side);
  if (found != maps.end()) return found->second;
  return maps
      .emplace(side, omninav::testing::rendered_grid_map(
                         room_for(side), bench_render(),
                         "grid:x0=" + std::to_string(kMarginM) + ",y0=" + std::to_string(kMarginM) +
                             ",nx=" + std::to_string(side) + ",ny=" + std::to_string(side) +
                             ",spacing_m=" + std::to_string(kSpacing),
                         "lattice_bench.cpp"))
      .first->second;
}

void organise_rendered_grid(benchmark::State& state) {
  memory::VisualMemory map = grid_map(static_cast<int>(state.range(0)));
  lattice::OrganiseParams params;
  params.step_m = kSpacing;
  lattice::OrganiseResult result;
  for (auto _ : state) result = lattice::organise(map, params);
  const double places = static_cast<double>(map.place_count());
  state.counters["places"] = places;
  state.counters["pairs"] = places * (places - 1) / 2;
  state.counters["springs"] = static_cast<double>(result.lattice.springs_given);
  state.counters["springs_kept"] = static_cast<double>(result.lattice.springs_kept);
  state.counters["motions"] = static_cast<double>(result.motions.size());
  const std::optional<evaluation::LatticeScore> score = evaluation::score_lattice(map, false);
  if (score) {
    state.counters["rmse_spacings"] = score->rmse.all;
    state.counters["rmse_interior"] = score->rmse.interior;
  }
}

// A driven tour of the room of a side × side grid, explored once per process.
const memory::VisualMemory& driven_map(int side) {
  static std::map<int, memory::VisualMemory> maps;
  const auto found = maps.find(side);
  if (found != maps.end()) return found->second;
  const double far = kMarginM + (side - 1) * kSpacing;
  memory::VisualMemory map = omninav::testing::explored_stream(
      omninav::testing::rendered_frames(
          room_for(side), bench_render(),
          "tour:x0=" + std::to_string(kMarginM) + ",y0=" + std::to_string(kMarginM) +
              ",x1=" + std::to_string(far) + ",y1=" + std::to_string(far) +
              ",lane_m=0.3,speed_m_s=0.3,fps=1,turn_rate_deg_s=90,odometry_noise=0.05",
          "tour"),
      {kSpacing, memory::HeadingPolicy::kTruth, true}, "tour", "lattice_bench.cpp");
  return maps.emplace(side, std::move(map)).first->second;
}

void organise_driven_tour(benchmark::State& state) {
  memory::VisualMemory map = driven_map(static_cast<int>(state.range(0)));
  lattice::OrganiseResult result;
  for (auto _ : state) result = lattice::organise(map, {});
  state.counters["places"] = static_cast<double>(map.place_count());
  state.counters["travelled"] = result.travelled_links;
  state.counters["revisits"] = result.revisits;
  state.counters["switched_off"] = result.revisits_switched_off;
  const std::optional<evaluation::LatticeScore> score = evaluation::score_lattice(map, false);
  if (score) {
    state.counters["rmse_spacings"] = score->rmse.all;
    state.counters["rmse_interior"] = score->rmse.interior;
  }
}

// Tours of the 36², 60² and 134² grids' rooms: about 700, 1,900 and 10,000 places (furniture
// takes its share of the floor, and a place every 30 cm by the odometry skips a frame where
// the odometry measured a step short of it).
BENCHMARK(organise_driven_tour)
    ->Arg(36)
    ->Arg(60)
    ->Arg(134)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// 36² and 114² grid points: about 1,000 and 10,000 places once furniture takes its share.
BENCHMARK(organise_rendered_grid)->Arg(36)->Arg(114)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
