#include "omninav/sim/room.hpp"

#include <opencv2/core.hpp>

#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "room_textures.hpp"
#include "world_builder.hpp"

namespace omninav::sim {
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
  std::string walls = params.plain_walls ? "plain" : "textured";
  section.read("walls", walls, {"plain", "textured"});
  params.plain_walls = walls == "plain";
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
  using build::add_box;
  using build::add_material;
  using build::add_quad;
  using build::add_wall;
  using build::overlaps;
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
    cv::Mat texture;
    if (params.plain_walls) {
      const cv::Scalar paint = textures::random_colour(rng, 140, 235);
      texture = textures::painted_wall(length_m, params.height_m, ppm, paint, false, rng);
    } else {
      texture = textures::wall(length_m, params.height_m, ppm, rng);
    }
    const int material = add_material(world, "wall " + std::to_string(side), std::move(texture));
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
