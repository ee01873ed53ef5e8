#include "omninav/sim/house.hpp"

#include <algorithm>
#include <cmath>

#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "room_textures.hpp"
#include "world_builder.hpp"

namespace omninav::sim {
namespace {

constexpr double kWall_m = 0.12;  // thickness of the walls between rooms
constexpr double kDoorHeight_m = 2.05;
constexpr double kEpsilon_m = 1e-6;

// A doorway through a wall. The wall runs along x (between a room and the corridor) when
// `along_x`, else along y (between two rooms of a row); `wall_low`/`wall_high` are its faces
// across, `from`/`to` the opening along it.
struct Door {
  bool along_x = true;
  double wall_low = 0.0, wall_high = 0.0;
  double from = 0.0, to = 0.0;
};

struct Area {
  std::string name;
  FloorBox inside;
};

// Paints far apart in hue, shuffled per house so that neighbouring rooms differ (BGR).
const std::array<cv::Vec3f, 11> kPaints{{{150, 225, 240},
                                         {235, 205, 170},
                                         {160, 200, 170},
                                         {150, 170, 235},
                                         {225, 180, 200},
                                         {180, 205, 225},
                                         {205, 230, 190},
                                         {205, 205, 205},
                                         {170, 200, 245},
                                         {190, 190, 120},
                                         {170, 160, 210}}};

// One face of an area's wall, from `from` to `to` (the area on its left), floor to `height`,
// with the doorways that cut it: solid pieces full height, lintels above the openings. Its
// texture spans the whole face once.
void add_wall_with_openings(World& world, cv::Vec2f from, cv::Vec2f to, float height,
                            const std::vector<std::pair<double, double>>& openings, int material) {
  const cv::Vec2f direction = to - from;
  const double length = cv::norm(direction);
  const auto point = [&](double along, float z) {
    const cv::Vec2f p = from + direction * static_cast<float>(along / length);
    return cv::Vec3f(p[0], p[1], z);
  };
  const auto piece = [&](double a, double b, float bottom, float top) {
    const float u0 = static_cast<float>(a / length), u1 = static_cast<float>(b / length);
    const float v0 = bottom / height, v1 = top / height;
    build::add_quad(world, {point(a, bottom), point(b, bottom), point(b, top), point(a, top)},
                    {cv::Vec2f(u0, v0), cv::Vec2f(u1, v0), cv::Vec2f(u1, v1), cv::Vec2f(u0, v1)},
                    material);
  };
  double done = 0.0;
  for (const auto& [a, b] : openings) {
    if (a > done) piece(done, a, 0.f, height);
    piece(a, b, static_cast<float>(kDoorHeight_m), height);
    done = b;
  }
  if (done < length) piece(done, length, 0.f, height);
}

// The openings of `doors` in the face of an area's wall from `from` to `to`, as distances
// along it, sorted.
std::vector<std::pair<double, double>> openings_in(const std::vector<Door>& doors, cv::Vec2f from,
                                                   cv::Vec2f to) {
  std::vector<std::pair<double, double>> openings;
  const bool along_x = std::abs(from[1] - to[1]) < kEpsilon_m;
  const double line = along_x ? from[1] : from[0];
  const double start = along_x ? from[0] : from[1];
  const double end = along_x ? to[0] : to[1];
  for (const Door& door : doors) {
    if (door.along_x != along_x) continue;
    if (std::abs(door.wall_low - line) > 1e-4 && std::abs(door.wall_high - line) > 1e-4) continue;
    if (door.to <= std::min(start, end) || door.from >= std::max(start, end)) continue;
    const double a = std::abs(door.from - start), b = std::abs(door.to - start);
    openings.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(openings.begin(), openings.end());
  return openings;
}

// The jambs and the lintel's underside of a doorway, closing the wall's thickness, and the
// threshold on the floor between them.
void add_door_frame(World& world, const Door& door, int material, int threshold) {
  const float height = static_cast<float>(kDoorHeight_m);
  const auto corner = [&](double along, double across, float z) {
    return door.along_x ? cv::Vec3f(static_cast<float>(along), static_cast<float>(across), z)
                        : cv::Vec3f(static_cast<float>(across), static_cast<float>(along), z);
  };
  const std::array<cv::Vec2f, 4> uv{cv::Vec2f(0.f, 0.f), cv::Vec2f(1.f, 0.f), cv::Vec2f(1.f, 1.f),
                                    cv::Vec2f(0.f, 1.f)};
  for (const double along : {door.from, door.to}) {
    build::add_quad(world,
                    {corner(along, door.wall_low, 0.f), corner(along, door.wall_high, 0.f),
                     corner(along, door.wall_high, height), corner(along, door.wall_low, height)},
                    uv, material);
  }
  for (const auto& [z, surface] : {std::pair{height, material}, std::pair{0.f, threshold}}) {
    build::add_quad(world,
                    {corner(door.from, door.wall_low, z), corner(door.to, door.wall_low, z),
                     corner(door.to, door.wall_high, z), corner(door.from, door.wall_high, z)},
                    uv, surface);
  }
}

// The wall's obstacle boxes between `low` and `high` along it, left open at the doorways.
void add_wall_obstacles(World& world, bool along_x, double start, double end, double wall_low,
                        double wall_high, const std::vector<Door>& doors) {
  std::vector<std::pair<double, double>> gaps;
  for (const Door& door : doors) {
    if (door.along_x == along_x && std::abs(door.wall_low - wall_low) < 1e-4) {
      gaps.emplace_back(door.from, door.to);
    }
  }
  std::sort(gaps.begin(), gaps.end());
  double done = start;
  const auto add = [&](double a, double b) {
    if (b - a < kEpsilon_m) return;
    world.obstacles.push_back(along_x ? FloorBox{a, wall_low, b, wall_high}
                                      : FloorBox{wall_low, a, wall_high, b});
  };
  for (const auto& [a, b] : gaps) {
    add(done, a);
    done = b;
  }
  add(done, end);
}

// A table: a top 4 cm thick at `height` on four legs, open underneath (a low camera sees
// through it).
void add_table(World& world, const FloorBox& box, float height, int material) {
  constexpr double kLeg_m = 0.05, kInset_m = 0.04;
  build::add_box(world, box, height, material, height - 0.04f);
  for (const double x : {box.min_x_m + kInset_m, box.max_x_m - kInset_m - kLeg_m}) {
    for (const double y : {box.min_y_m + kInset_m, box.max_y_m - kInset_m - kLeg_m}) {
      build::add_box(world, {x, y, x + kLeg_m, y + kLeg_m}, height - 0.04f, material);
    }
  }
}

// The widths of one row of rooms along the corridor.
std::vector<double> row_widths(int count, const HouseParams& params, cv::RNG& rng) {
  std::vector<double> widths;
  for (int i = 0; i < count; ++i)
    widths.push_back(rng.uniform(params.room_min_m, params.room_max_m));
  return widths;
}

// Where the rooms, the corridor and the doorways are.
struct HousePlan {
  double length = 0.0;  // along x, both rows of rooms and the corridor
  double south_depth = 0.0, corridor_low = 0.0, corridor_high = 0.0, north_low = 0.0;
  double north_high = 0.0;
  std::vector<Area> areas;  // the rooms, then the corridor
  std::vector<Door> doors;
};

// Two rows of rooms, south (y from 0) and north, either side of the corridor; each room has a
// doorway to the corridor, and some a doorway to the next room of the row.
HousePlan plan_house(const HouseParams& params, cv::RNG& rng) {
  HousePlan plan;
  const int south_count = (params.rooms + 1) / 2, north_count = params.rooms / 2;
  std::vector<double> south = row_widths(south_count, params, rng);
  std::vector<double> north = row_widths(north_count, params, rng);
  const auto row_length = [](const std::vector<double>& widths) {
    double length = kWall_m * (static_cast<double>(widths.size()) - 1.0);
    for (double w : widths) length += w;
    return length;
  };
  plan.length = std::max(row_length(south), row_length(north));
  south.back() += plan.length - row_length(south);  // the shorter row's last room is stretched
  north.back() += plan.length - row_length(north);
  plan.south_depth = rng.uniform(params.room_min_m, params.room_max_m);
  const double north_depth = rng.uniform(params.room_min_m, params.room_max_m);
  plan.corridor_low = plan.south_depth + kWall_m;
  plan.corridor_high = plan.corridor_low + params.corridor_width_m;
  plan.north_low = plan.corridor_high + kWall_m;
  plan.north_high = plan.north_low + north_depth;

  const double door = params.door_width_m;
  const auto door_at = [&](double low, double high) {
    const double centre = rng.uniform(low + 0.3 + door / 2.0, high - 0.3 - door / 2.0);
    return std::pair<double, double>(centre - door / 2.0, centre + door / 2.0);
  };
  const auto add_row = [&](const std::vector<double>& widths, double y_low, double y_high,
                           bool is_south) {
    double x = 0.0;
    for (std::size_t i = 0; i < widths.size(); ++i) {
      const FloorBox inside{x, y_low, x + widths[i], y_high};
      plan.areas.push_back({"room " + std::to_string(plan.areas.size() + 1), inside});
      const auto [from, to] = door_at(inside.min_x_m, inside.max_x_m);
      plan.doors.push_back(is_south ? Door{true, plan.south_depth, plan.corridor_low, from, to}
                                    : Door{true, plan.corridor_high, plan.north_low, from, to});
      if (i + 1 < widths.size() && rng.uniform(0.0, 1.0) < 0.4) {
        const auto [a, b] = door_at(y_low, y_high);
        plan.doors.push_back({false, inside.max_x_m, inside.max_x_m + kWall_m, a, b});
      }
      x += widths[i] + kWall_m;
    }
  };
  add_row(south, 0.0, plan.south_depth, true);
  add_row(north, plan.north_low, plan.north_high, false);
  plan.areas.push_back({"corridor", {0.0, plan.corridor_low, plan.length, plan.corridor_high}});
  return plan;
}

// One of three floors for a room, planks for the corridor.
cv::Mat area_floor(const Area& area, double ppm, cv::RNG& rng) {
  const double width_m = area.inside.max_x_m - area.inside.min_x_m;
  const double depth_m = area.inside.max_y_m - area.inside.min_y_m;
  switch (area.name == "corridor" ? 1 : rng.uniform(0, 3)) {
    case 0:
      return textures::floor(width_m, depth_m, ppm, rng);
    case 1:
      return textures::planks(width_m, depth_m, ppm, rng);
    default:
      return textures::carpet(width_m, depth_m, ppm, rng);
  }
}

// An area's look: `paint` on its four walls (cut by the doorways), its own floor and ceiling;
// and its name as a region.
void dress_area(World& world, const Area& area, const std::vector<Door>& doors,
                const HouseParams& params, cv::Scalar paint, cv::RNG& rng) {
  const double ppm = params.texture_px_per_m;
  const float height = static_cast<float>(params.height_m);
  const FloorBox& box = area.inside;
  const float x0 = static_cast<float>(box.min_x_m), x1 = static_cast<float>(box.max_x_m);
  const float y0 = static_cast<float>(box.min_y_m), y1 = static_cast<float>(box.max_y_m);
  const std::array<cv::Vec2f, 5> corners{cv::Vec2f(x0, y0), cv::Vec2f(x1, y0), cv::Vec2f(x1, y1),
                                         cv::Vec2f(x0, y1), cv::Vec2f(x0, y0)};
  for (int side = 0; side < 4; ++side) {
    const double side_m = cv::norm(corners[side + 1] - corners[side]);
    const int material =
        build::add_material(world, area.name + " wall " + std::to_string(side),
                            textures::painted_wall(side_m, params.height_m, ppm, paint, true, rng));
    add_wall_with_openings(world, corners[side], corners[side + 1], height,
                           openings_in(doors, corners[side], corners[side + 1]), material);
  }
  const double width_m = box.max_x_m - box.min_x_m, depth_m = box.max_y_m - box.min_y_m;
  cv::Mat floor_texture = area_floor(area, ppm, rng);
  const std::array<cv::Vec2f, 4> whole{cv::Vec2f(0.f, 0.f), cv::Vec2f(1.f, 0.f),
                                       cv::Vec2f(1.f, 1.f), cv::Vec2f(0.f, 1.f)};
  build::add_quad(world,
                  {cv::Vec3f(x0, y0, 0.f), cv::Vec3f(x1, y0, 0.f), cv::Vec3f(x1, y1, 0.f),
                   cv::Vec3f(x0, y1, 0.f)},
                  whole,
                  build::add_material(world, area.name + " floor", std::move(floor_texture)));
  build::add_quad(world,
                  {cv::Vec3f(x0, y0, height), cv::Vec3f(x1, y0, height), cv::Vec3f(x1, y1, height),
                   cv::Vec3f(x0, y1, height)},
                  whole,
                  build::add_material(world, area.name + " ceiling",
                                      textures::ceiling(width_m, depth_m, ppm, rng)));
  world.regions.push_back({area.name, box});
}

// Every area in its own paint (far apart in hue, shuffled per house so that neighbouring rooms
// differ), then the doorways' frames.
void dress_house(World& world, const HousePlan& plan, const HouseParams& params, cv::RNG& rng) {
  std::vector<int> paint_order(kPaints.size());
  for (std::size_t i = 0; i < paint_order.size(); ++i) paint_order[i] = static_cast<int>(i);
  for (std::size_t i = paint_order.size() - 1; i > 0; --i) {
    std::swap(paint_order[i], paint_order[rng.uniform(0, static_cast<int>(i) + 1)]);
  }
  const int frame_material = build::add_colour(world, "door frame", {225.f, 235.f, 240.f});
  for (std::size_t index = 0; index < plan.areas.size(); ++index) {
    cv::Scalar paint(kPaints[paint_order[index % kPaints.size()]]);
    paint *= rng.uniform(0.9, 1.05);
    dress_area(world, plan.areas[index], plan.doors, params, paint, rng);
  }
  const int threshold_material = build::add_colour(world, "threshold", {60.f, 85.f, 110.f});
  for (const Door& d : plan.doors) add_door_frame(world, d, frame_material, threshold_material);
}

// Walls between areas are obstacles, open at the doorways; the outer walls are the floor's edge.
void add_inner_walls(World& world, const HousePlan& plan) {
  add_wall_obstacles(world, true, 0.0, plan.length, plan.south_depth, plan.corridor_low,
                     plan.doors);
  add_wall_obstacles(world, true, 0.0, plan.length, plan.corridor_high, plan.north_low, plan.doors);
  for (const Area& area : plan.areas) {
    if (area.name == "corridor" || area.inside.max_x_m >= plan.length - kEpsilon_m) continue;
    add_wall_obstacles(world, false, area.inside.min_y_m, area.inside.max_y_m, area.inside.max_x_m,
                       area.inside.max_x_m + kWall_m, plan.doors);
  }
}

// Up to params.furniture tables and boxes in `area`, clear of the walls and other obstacles by
// kGap_m and of `keep_clear`.
void furnish_room(World& world, const Area& area, const std::vector<FloorBox>& keep_clear,
                  const HouseParams& params, cv::RNG& rng) {
  constexpr double kGap_m = 0.4;
  const FloorBox& room = area.inside;
  int placed = 0;
  for (int attempt = 0; attempt < 200 * params.furniture && placed < params.furniture; ++attempt) {
    const double side_x = rng.uniform(0.4, 1.4), side_y = rng.uniform(0.4, 1.4);
    const double free_x = room.max_x_m - room.min_x_m - 2 * kGap_m - side_x;
    const double free_y = room.max_y_m - room.min_y_m - 2 * kGap_m - side_y;
    if (free_x <= 0.0 || free_y <= 0.0) continue;
    const double x = room.min_x_m + kGap_m + rng.uniform(0.0, free_x);
    const double y = room.min_y_m + kGap_m + rng.uniform(0.0, free_y);
    const FloorBox box{x, y, x + side_x, y + side_y};
    bool free = true;
    for (const FloorBox& other : world.obstacles)
      free = free && !build::overlaps(box, other, kGap_m);
    for (const FloorBox& clear : keep_clear) free = free && !build::overlaps(box, clear, 0.0);
    if (!free) continue;
    const int material =
        build::add_material(world, area.name + " furniture " + std::to_string(placed),
                            textures::furniture(params.texture_px_per_m, rng));
    if (rng.uniform(0.0, 1.0) < 0.35) {
      add_table(world, box, static_cast<float>(rng.uniform(0.45, 0.8)), material);
    } else {  // a cupboard, a bed, a sofa, a shelf...
      build::add_box(world, box, static_cast<float>(rng.uniform(0.4, 1.9)), material);
    }
    world.obstacles.push_back(box);
    ++placed;
  }
  if (placed < params.furniture) {
    log_warning("house: placed " + std::to_string(placed) + " of " +
                std::to_string(params.furniture) + " furniture boxes in " + area.name);
  }
}

// Furniture along the rooms, clear of the doorways (a 1 m deep space in front of each).
void furnish_house(World& world, const HousePlan& plan, const HouseParams& params, cv::RNG& rng) {
  std::vector<FloorBox> keep_clear;
  for (const Door& d : plan.doors) {
    const double margin = 0.2;
    keep_clear.push_back(
        d.along_x ? FloorBox{d.from - margin, d.wall_low - 1.0, d.to + margin, d.wall_high + 1.0}
                  : FloorBox{d.wall_low - 1.0, d.from - margin, d.wall_high + 1.0, d.to + margin});
  }
  for (const Area& area : plan.areas) {
    if (area.name != "corridor") furnish_room(world, area, keep_clear, params, rng);
  }
}

}  // namespace

World make_house(const HouseParams& params) {
  if (params.room_min_m > params.room_max_m) {
    throw UsageError("house: room_min_m (" + std::to_string(params.room_min_m) +
                     ") must not exceed room_max_m (" + std::to_string(params.room_max_m) + ")");
  }
  World world;
  world.name = "house";
  cv::RNG rng(static_cast<std::uint64_t>(params.seed) * 7919 + 17);
  const HousePlan plan = plan_house(params, rng);
  world.floor = {0.0, 0.0, plan.length, plan.north_high};
  dress_house(world, plan, params, rng);
  add_inner_walls(world, plan);
  furnish_house(world, plan, params, rng);
  return world;
}

}  // namespace omninav::sim
