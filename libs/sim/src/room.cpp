#include "omninav/sim/room.hpp"

#include <opencv2/core.hpp>

#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "room_textures.hpp"

namespace omninav::sim {
namespace {

int add_material(World& world, std::string name, cv::Mat texture) {
  world.textures.push_back(std::move(texture));
  world.materials.push_back(
      {std::move(name), {255.f, 255.f, 255.f}, static_cast<int>(world.textures.size()) - 1});
  return static_cast<int>(world.materials.size()) - 1;
}

// A planar quad a-b-c-d (in order around its edge) as two triangles, with the texture
// coordinates of its corners.
void add_quad(World& world, const std::array<cv::Vec3f, 4>& corners,
              const std::array<cv::Vec2f, 4>& uv, int material) {
  const int first = static_cast<int>(world.vertices.size());
  world.vertices.insert(world.vertices.end(), corners.begin(), corners.end());
  world.triangles.push_back({{first, first + 1, first + 2}, {uv[0], uv[1], uv[2]}, material});
  world.triangles.push_back({{first, first + 2, first + 3}, {uv[0], uv[2], uv[3]}, material});
}

// A vertical wall from (x0, y0) to (x1, y1), floor to `height`, its texture spanning it once.
void add_wall(World& world, cv::Vec2f from, cv::Vec2f to, float height, int material) {
  add_quad(world,
           {cv::Vec3f(from[0], from[1], 0.f), cv::Vec3f(to[0], to[1], 0.f),
            cv::Vec3f(to[0], to[1], height), cv::Vec3f(from[0], from[1], height)},
           {cv::Vec2f(0.f, 0.f), cv::Vec2f(1.f, 0.f), cv::Vec2f(1.f, 1.f), cv::Vec2f(0.f, 1.f)},
           material);
}

// A furniture box: four sides and a top, its 1 m texture tiled in metres along each face.
void add_box(World& world, const FloorBox& box, float height, int material) {
  const float x0 = static_cast<float>(box.min_x_m), x1 = static_cast<float>(box.max_x_m);
  const float y0 = static_cast<float>(box.min_y_m), y1 = static_cast<float>(box.max_y_m);
  const std::array<cv::Vec2f, 5> ring{cv::Vec2f(x0, y0), cv::Vec2f(x1, y0), cv::Vec2f(x1, y1),
                                      cv::Vec2f(x0, y1), cv::Vec2f(x0, y0)};
  float along = 0.f;  // texture continues around the box
  for (int side = 0; side < 4; ++side) {
    const cv::Vec2f from = ring[side], to = ring[side + 1];
    const float length = static_cast<float>(cv::norm(to - from));
    add_quad(world,
             {cv::Vec3f(from[0], from[1], 0.f), cv::Vec3f(to[0], to[1], 0.f),
              cv::Vec3f(to[0], to[1], height), cv::Vec3f(from[0], from[1], height)},
             {cv::Vec2f(along, 0.f), cv::Vec2f(along + length, 0.f),
              cv::Vec2f(along + length, height), cv::Vec2f(along, height)},
             material);
    along += length;
  }
  add_quad(world,
           {cv::Vec3f(x0, y0, height), cv::Vec3f(x1, y0, height), cv::Vec3f(x1, y1, height),
            cv::Vec3f(x0, y1, height)},
           {cv::Vec2f(x0, y0), cv::Vec2f(x1, y0), cv::Vec2f(x1, y1), cv::Vec2f(x0, y1)}, material);
}

bool overlaps(const FloorBox& a, const FloorBox& b, double gap_m) {
  return a.min_x_m < b.max_x_m + gap_m && b.min_x_m < a.max_x_m + gap_m &&
         a.min_y_m < b.max_y_m + gap_m && b.min_y_m < a.max_y_m + gap_m;
}

}  // namespace

void load_room_params(const ConfigReader& section, RoomParams& params) {
  section.read("size_x_m", params.size_x_m, 1.0, 100.0);
  section.read("size_y_m", params.size_y_m, 1.0, 100.0);
  section.read("height_m", params.height_m, 0.5, 20.0);
  section.read("furniture_count", params.furniture_count, 0, 200);
  section.read("furniture_min_side_m", params.furniture_min_side_m, 0.05, 10.0);
  section.read("furniture_max_side_m", params.furniture_max_side_m, 0.05, 10.0);
  section.read("furniture_min_height_m", params.furniture_min_height_m, 0.05, 20.0);
  section.read("furniture_max_height_m", params.furniture_max_height_m, 0.05, 20.0);
  section.read("furniture_gap_m", params.furniture_gap_m, 0.0, 10.0);
  section.read("texture_px_per_m", params.texture_px_per_m, 10.0, 1000.0);
  int seed = static_cast<int>(params.seed);
  section.read("seed", seed, 0, 1'000'000'000);
  params.seed = static_cast<std::uint32_t>(seed);
  if (params.furniture_min_side_m > params.furniture_max_side_m ||
      params.furniture_min_height_m > params.furniture_max_height_m) {
    throw ConfigError(section.source_name() +
                      ": room furniture minimum sizes must not exceed the maximum sizes");
  }
}

World make_room(const RoomParams& params) {
  World world;
  world.name = "room";
  cv::RNG rng(params.seed);
  const float lx = static_cast<float>(params.size_x_m);
  const float ly = static_cast<float>(params.size_y_m);
  const float height = static_cast<float>(params.height_m);
  const double ppm = params.texture_px_per_m;

  // Walls counter-clockwise seen from above, each with its own texture.
  const std::array<cv::Vec2f, 5> corners{cv::Vec2f(0.f, 0.f), cv::Vec2f(lx, 0.f), cv::Vec2f(lx, ly),
                                         cv::Vec2f(0.f, ly), cv::Vec2f(0.f, 0.f)};
  for (int side = 0; side < 4; ++side) {
    const double length_m = cv::norm(corners[side + 1] - corners[side]);
    const int material = add_material(world, "wall " + std::to_string(side),
                                      textures::wall(length_m, params.height_m, ppm, rng));
    add_wall(world, corners[side], corners[side + 1], height, material);
  }
  const int floor_material =
      add_material(world, "floor", textures::floor(params.size_x_m, params.size_y_m, ppm, rng));
  add_quad(world,
           {cv::Vec3f(0.f, 0.f, 0.f), cv::Vec3f(lx, 0.f, 0.f), cv::Vec3f(lx, ly, 0.f),
            cv::Vec3f(0.f, ly, 0.f)},
           {cv::Vec2f(0.f, 0.f), cv::Vec2f(1.f, 0.f), cv::Vec2f(1.f, 1.f), cv::Vec2f(0.f, 1.f)},
           floor_material);
  const int ceiling_material =
      add_material(world, "ceiling", textures::ceiling(params.size_x_m, params.size_y_m, ppm, rng));
  add_quad(world,
           {cv::Vec3f(0.f, 0.f, height), cv::Vec3f(lx, 0.f, height), cv::Vec3f(lx, ly, height),
            cv::Vec3f(0.f, ly, height)},
           {cv::Vec2f(0.f, 0.f), cv::Vec2f(1.f, 0.f), cv::Vec2f(1.f, 1.f), cv::Vec2f(0.f, 1.f)},
           ceiling_material);
  world.floor = {0.0, 0.0, params.size_x_m, params.size_y_m};

  // Furniture by rejection sampling; a crowded room may get fewer boxes than asked for.
  constexpr int kAttemptsPerBox = 200;
  const double gap = params.furniture_gap_m;
  for (int attempt = 0; attempt < kAttemptsPerBox * params.furniture_count &&
                        static_cast<int>(world.obstacles.size()) < params.furniture_count;
       ++attempt) {
    const double side_x = rng.uniform(params.furniture_min_side_m, params.furniture_max_side_m);
    const double side_y = rng.uniform(params.furniture_min_side_m, params.furniture_max_side_m);
    if (side_x + 2 * gap >= params.size_x_m || side_y + 2 * gap >= params.size_y_m) continue;
    const double x = rng.uniform(gap, params.size_x_m - gap - side_x);
    const double y = rng.uniform(gap, params.size_y_m - gap - side_y);
    const FloorBox box{x, y, x + side_x, y + side_y};
    bool free = true;
    for (const FloorBox& other : world.obstacles) free = free && !overlaps(box, other, gap);
    if (!free) continue;
    const double box_height =
        rng.uniform(params.furniture_min_height_m, params.furniture_max_height_m);
    const int material = add_material(world, "furniture " + std::to_string(world.obstacles.size()),
                                      textures::furniture(ppm, rng));
    add_box(world, box, static_cast<float>(box_height), material);
    world.obstacles.push_back(box);
  }
  if (static_cast<int>(world.obstacles.size()) < params.furniture_count) {
    log_warning("room: placed " + std::to_string(world.obstacles.size()) + " of " +
                std::to_string(params.furniture_count) + " furniture boxes (no free space left)");
  }
  return world;
}

}  // namespace omninav::sim
