// The spring lattice's speed (issue 5: 1,000 places organised in ≤ 2 s, 10,000 in ≤ 30 s on
// one core). Places on a square grid walked boustrophedon, springs to the places within the
// correlation range with 10 % noise, and the motion chain, as an exploration gives them.
// Run: build/bin/lattice_bench
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "omninav/lattice/spring_lattice.hpp"

namespace {

using omninav::lattice::MotionMeasurement;
using omninav::lattice::SpringMeasurement;

void organise_grid(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const double spacing = 0.3, range = 0.9;
  std::vector<Eigen::Vector2d> truth;
  for (int iy = 0; iy < side; ++iy) {
    for (int i = 0; i < side; ++i)
      truth.emplace_back((iy % 2 == 0 ? i : side - 1 - i) * spacing, iy * spacing);
  }
  std::mt19937 random(1);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<SpringMeasurement> springs;
  // Neighbours by grid index: the same pairs a k-nearest search over signatures would give.
  const int reach = static_cast<int>(std::ceil(range / spacing));
  for (int a = 0; a < static_cast<int>(truth.size()); ++a) {
    for (int b = a + 1; b < static_cast<int>(truth.size()); ++b) {
      const Eigen::Vector2d delta = truth[b] - truth[a];
      if (std::abs(delta.y()) > reach * spacing + 1e-9) break;  // rows further on are out of range
      if (delta.norm() <= range) springs.push_back({a, b, delta.norm() * (1.0 + noise(random))});
    }
  }
  std::vector<MotionMeasurement> motions;
  for (int i = 0; i + 1 < static_cast<int>(truth.size()); ++i) {
    const Eigen::Vector2d step = truth[i + 1] - truth[i];
    motions.push_back(
        {i, i + 1, std::atan2(step.y(), step.x()) + noise(random), step.norm(), 0.15, 0.03});
  }
  omninav::lattice::LatticeParams params;
  params.correlation_range_m = range;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        omninav::lattice::solve_lattice(static_cast<int>(truth.size()), springs, motions, params));
  }
  state.counters["places"] = static_cast<double>(truth.size());
  state.counters["springs"] = static_cast<double>(springs.size());
}

BENCHMARK(organise_grid)->Arg(32)->Arg(100)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
