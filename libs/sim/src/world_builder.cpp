#include "world_builder.hpp"

namespace omninav::sim::build {

int add_material(World& world, std::string name, cv::Mat texture) {
  world.textures.push_back(std::move(texture));
  world.materials.push_back(
      {std::move(name), {255.f, 255.f, 255.f}, static_cast<int>(world.textures.size()) - 1});
  return static_cast<int>(world.materials.size()) - 1;
}

int add_colour(World& world, std::string name, const cv::Vec3f& colour_bgr) {
  world.materials.push_back({std::move(name), colour_bgr, -1});
  return static_cast<int>(world.materials.size()) - 1;
}

void add_quad(World& world, const std::array<cv::Vec3f, 4>& corners,
              const std::array<cv::Vec2f, 4>& uv, int material) {
  const int first = static_cast<int>(world.vertices.size());
  world.vertices.insert(world.vertices.end(), corners.begin(), corners.end());
  world.triangles.push_back({{first, first + 1, first + 2}, {uv[0], uv[1], uv[2]}, material});
  world.triangles.push_back({{first, first + 2, first + 3}, {uv[0], uv[2], uv[3]}, material});
}

void add_wall(World& world, cv::Vec2f from, cv::Vec2f to, float height, int material) {
  add_quad(world,
           {cv::Vec3f(from[0], from[1], 0.f), cv::Vec3f(to[0], to[1], 0.f),
            cv::Vec3f(to[0], to[1], height), cv::Vec3f(from[0], from[1], height)},
           {cv::Vec2f(0.f, 0.f), cv::Vec2f(1.f, 0.f), cv::Vec2f(1.f, 1.f), cv::Vec2f(0.f, 1.f)},
           material);
}

void add_box(World& world, const FloorBox& box, float top, int material, float bottom) {
  const float x0 = static_cast<float>(box.min_x_m), x1 = static_cast<float>(box.max_x_m);
  const float y0 = static_cast<float>(box.min_y_m), y1 = static_cast<float>(box.max_y_m);
  const std::array<cv::Vec2f, 5> ring{cv::Vec2f(x0, y0), cv::Vec2f(x1, y0), cv::Vec2f(x1, y1),
                                      cv::Vec2f(x0, y1), cv::Vec2f(x0, y0)};
  float along = 0.f;  // texture continues around the box
  for (int side = 0; side < 4; ++side) {
    const cv::Vec2f from = ring[side], to = ring[side + 1];
    const float length = static_cast<float>(cv::norm(to - from));
    add_quad(world,
             {cv::Vec3f(from[0], from[1], bottom), cv::Vec3f(to[0], to[1], bottom),
              cv::Vec3f(to[0], to[1], top), cv::Vec3f(from[0], from[1], top)},
             {cv::Vec2f(along, bottom), cv::Vec2f(along + length, bottom),
              cv::Vec2f(along + length, top), cv::Vec2f(along, top)},
             material);
    along += length;
  }
  add_quad(world,
           {cv::Vec3f(x0, y0, top), cv::Vec3f(x1, y0, top), cv::Vec3f(x1, y1, top),
            cv::Vec3f(x0, y1, top)},
           {cv::Vec2f(x0, y0), cv::Vec2f(x1, y0), cv::Vec2f(x1, y1), cv::Vec2f(x0, y1)}, material);
}

bool overlaps(const FloorBox& a, const FloorBox& b, double gap_m) {
  return a.min_x_m < b.max_x_m + gap_m && b.min_x_m < a.max_x_m + gap_m &&
         a.min_y_m < b.max_y_m + gap_m && b.min_y_m < a.max_y_m + gap_m;
}

}  // namespace omninav::sim::build
