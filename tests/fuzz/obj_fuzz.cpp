// libFuzzer target: a Wavefront OBJ world (libs/sim load_obj_world, through Debian's
// tinyobjloader), then one small panorama rendered in it from the middle of its floor, so that
// whatever the loader accepts must also be a world Embree can trace. The scratch folder holds an
// MTL file (room.mtl, two materials, one of them textured with 0.png) that inputs may name.
// Seeds: tests/fuzz/corpus/obj (hand-made: a box, a textured quad, negative indices).
#include "fuzz_support.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/world.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace omninav;
  static const std::filesystem::path folder = [] {
    const std::filesystem::path dir = fuzz::folder_with_image("obj");
    fuzz::write_file(dir / "room.mtl",
                     "newmtl wall\nKd 0.8 0.7 0.6\nnewmtl poster\nKd 1 1 1\nmap_Kd 0.png\n");
    return dir;
  }();
  static const std::filesystem::path obj = folder / "world.obj";
  fuzz::write_file(obj, fuzz::as_text(data, size));
  return fuzz::expect_clean([] {
    const sim::World world = sim::load_obj_world(obj);
    sim::RenderParams params;
    params.geometry.width_px = 16;
    params.geometry.height_px = 4;
    params.rays_per_pixel = 1;
    const sim::Renderer renderer(world, params);
    const sim::FloorBox& floor = world.floor;
    (void)renderer.render({.x_m = (floor.min_x_m + floor.max_x_m) / 2,
                           .y_m = (floor.min_y_m + floor.max_y_m) / 2,
                           .z_m = 0.5});
  });
}
