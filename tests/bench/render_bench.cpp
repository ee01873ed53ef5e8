// The renderer's speed (target: ≤ 5 ms for a 360×45 panorama of the default room on one core),
// and on the other families: the field's ~200 000 grass triangles must stay fast too.
// Run: build/bin/render_bench
#include <benchmark/benchmark.h>

#include "omninav/sim/renderer.hpp"
#include "omninav/sim/room.hpp"
#include "omninav/sim/world_loader.hpp"

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

// A short walk through a family's world (default parameters) at camera height z_m.
void render_family(benchmark::State& state, const std::string& spec, double z_m) {
  const omninav::sim::World world = omninav::sim::load_world(spec, {});
  RenderParams params;
  params.geometry.width_px = 360;
  params.geometry.height_px = 45;
  const Renderer renderer(world, params);
  const double x0 = (world.floor.min_x_m + world.floor.max_x_m) / 2 - 1.5;
  const double y0 = (world.floor.min_y_m + world.floor.max_y_m) / 2;
  int frame = 0;
  for (auto _ : state) {
    const double x = x0 + 0.01 * (frame % 300);
    benchmark::DoNotOptimize(renderer.render(CameraPose{x, y0, z_m, 0.3 * frame, 0.0, 0.0}));
    ++frame;
  }
  state.counters["triangles"] = static_cast<double>(world.triangles.size());
}

BENCHMARK_CAPTURE(render_family, field_360x45_3rays_z10cm, std::string("field"), 0.1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_family, field_360x45_3rays_z150cm, std::string("field"), 1.5)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_family, field20000_360x45_3rays_z10cm, std::string("field:tussocks=20000"),
                  0.1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_family, house_360x45_3rays, std::string("house"), 1.0)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_family, office_360x45_3rays, std::string("office"), 1.0)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(render_default_room, 360x45_1ray, 360, 45, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_default_room, 360x45_3rays_default, 360, 45, 3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_default_room, 360x45_4rays, 360, 45, 4)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_default_room, 1080x135_3rays, 1080, 135, 3)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
