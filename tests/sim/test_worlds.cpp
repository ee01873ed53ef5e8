#include "test_worlds.hpp"

namespace omninav::sim::testing {
namespace {

int add_material(World& world, cv::Vec3f colour) {
  world.materials.push_back({"flat", colour, -1});
  return static_cast<int>(world.materials.size()) - 1;
}

void add_quad(World& world, std::array<cv::Vec3f, 4> corners, int material) {
  const int first = static_cast<int>(world.vertices.size());
  world.vertices.insert(world.vertices.end(), corners.begin(), corners.end());
  world.triangles.push_back({{first, first + 1, first + 2}, {}, material});
  world.triangles.push_back({{first, first + 2, first + 3}, {}, material});
}

}  // namespace

World horizon_hall(double half_m, double split_z_m, double height_m) {
  World world;
  world.name = "horizon hall";
  const float h = static_cast<float>(half_m), split = static_cast<float>(split_z_m);
  const float top = static_cast<float>(height_m);
  const int black = add_material(world, {0.f, 0.f, 0.f});
  const int white = add_material(world, {255.f, 255.f, 255.f});
  const int grey = add_material(world, {128.f, 128.f, 128.f});
  const std::array<cv::Vec2f, 5> ring{cv::Vec2f(-h, -h), cv::Vec2f(h, -h), cv::Vec2f(h, h),
                                      cv::Vec2f(-h, h), cv::Vec2f(-h, -h)};
  for (int side = 0; side < 4; ++side) {
    const cv::Vec2f a = ring[side], b = ring[side + 1];
    add_quad(world,
             {cv::Vec3f(a[0], a[1], 0.f), cv::Vec3f(b[0], b[1], 0.f), cv::Vec3f(b[0], b[1], split),
              cv::Vec3f(a[0], a[1], split)},
             black);
    add_quad(world,
             {cv::Vec3f(a[0], a[1], split), cv::Vec3f(b[0], b[1], split),
              cv::Vec3f(b[0], b[1], top), cv::Vec3f(a[0], a[1], top)},
             white);
  }
  add_quad(
      world,
      {cv::Vec3f(-h, -h, 0.f), cv::Vec3f(h, -h, 0.f), cv::Vec3f(h, h, 0.f), cv::Vec3f(-h, h, 0.f)},
      grey);
  add_quad(
      world,
      {cv::Vec3f(-h, -h, top), cv::Vec3f(h, -h, top), cv::Vec3f(h, h, top), cv::Vec3f(-h, h, top)},
      grey);
  world.floor = {-half_m, -half_m, half_m, half_m};
  return world;
}

void add_coloured_box(World& world, cv::Vec3f centre, float side_m, cv::Vec3f colour_bgr) {
  const int material = add_material(world, colour_bgr);
  const float s = side_m / 2.f;
  const cv::Vec3f c = centre;
  auto corner = [&](float dx, float dy, float dz) { return c + cv::Vec3f(dx, dy, dz); };
  add_quad(world, {corner(-s, -s, -s), corner(s, -s, -s), corner(s, -s, s), corner(-s, -s, s)},
           material);
  add_quad(world, {corner(s, -s, -s), corner(s, s, -s), corner(s, s, s), corner(s, -s, s)},
           material);
  add_quad(world, {corner(s, s, -s), corner(-s, s, -s), corner(-s, s, s), corner(s, s, s)},
           material);
  add_quad(world, {corner(-s, s, -s), corner(-s, -s, -s), corner(-s, -s, s), corner(-s, s, s)},
           material);
  add_quad(world, {corner(-s, -s, s), corner(s, -s, s), corner(s, s, s), corner(-s, s, s)},
           material);
  add_quad(world, {corner(-s, -s, -s), corner(-s, s, -s), corner(s, s, -s), corner(s, -s, -s)},
           material);
}

}  // namespace omninav::sim::testing
