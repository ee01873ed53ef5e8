// The renderer's speed (issue: ≤ 5 ms for a 360×45 panorama of the default room on one core).
// Run: build/bin/render_bench
#include <benchmark/benchmark.h>

#include "omninav/sim/renderer.hpp"
#include "omninav/sim/room.hpp"

namespace {

using omninav::CameraPose;
using omninav::sim::Renderer;
using omninav::sim::RenderParams;

// Renders a short walk across the default room so that the cost is averaged over views.
void render_default_room(benchmark::State& state, int width, int height, int rays_per_pixel) {
  const omninav::sim::World world = omninav::sim::make_room({});
  RenderParams params;
  params.geometry.width_px = width;
  params.geometry.height_px = height;
  params.rays_per_pixel = rays_per_pixel;
  const Renderer renderer(world, params);
  int frame = 0;
  for (auto _ : state) {
    const double x = 1.0 + 0.01 * (frame % 300);
    benchmark::DoNotOptimize(renderer.render(CameraPose{x, 2.2, 1.0, 0.3 * frame, 0.0, 0.0}));
    ++frame;
  }
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * width * height * rays_per_pixel,
                         benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(render_default_room, 360x45_1ray, 360, 45, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_default_room, 360x45_3rays_default, 360, 45, 3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_default_room, 360x45_4rays, 360, 45, 4)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_default_room, 1080x135_3rays, 1080, 135, 3)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
